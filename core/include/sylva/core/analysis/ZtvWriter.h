// ZtvWriter: writes a ViewshedResult as a georeferenced GeoTIFF through GDAL: three
// Float32 bands on the result's grid ("visible" 0/1, "count" of targets visible,
// "fraction" of the height visible, NaN = no data), the CRS given as WKT, DEFLATE
// compression, 256² tiles and internal overviews (nearest: 2, 4, 8 ... while the
// smaller side stays ≥ 16 cells). The file is written under a temporary name in the
// target's folder and renamed over the target only when complete, so a failure leaves
// nothing half-written and the previous file intact. The folder must exist.
// Failures return the reason ("<path>: <GDAL message>").
#pragma once

#include <filesystem>
#include <string>

#include "sylva/core/analysis/Viewshed.h"
#include "sylva/core/base/Result.h"

namespace sylva {

Status writeZtvGeoTiff(const std::filesystem::path& path, const ViewshedResult& result,
                       const std::string& crsWkt);

}  // namespace sylva
