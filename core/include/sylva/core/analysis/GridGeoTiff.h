// GridGeoTiff: writes Float32 bands on an analysis grid (GridGeometry) as a
// georeferenced GeoTIFF through GDAL: the CRS given as WKT, one named band per entry
// (NaN = no data), DEFLATE compression with the floating-point predictor, 256² tiles
// and internal overviews (nearest: 2, 4, 8 ... while the smaller side stays ≥ 16
// cells). The file is written under a temporary name in the target's folder and renamed
// over the target only when complete, so a failure leaves nothing half-written and the
// previous file intact. The folder must exist. Used by ZtvWriter and the shadow study.
// Failures return "<path>: <GDAL message>"; bands of the wrong size are programmer errors.
#pragma once

#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "sylva/core/analysis/ElevationGrid.h"
#include "sylva/core/base/Result.h"

namespace sylva {

struct GridBand {
    std::string name;                  // the band's description
    const std::vector<float>* values;  // width × height, row-major; not owned
};

Status writeGridGeoTiff(const std::filesystem::path& path, const GridGeometry& geometry,
                        std::span<const GridBand> bands, const std::string& crsWkt);

}  // namespace sylva
