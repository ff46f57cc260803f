// GdalDatasetPool: per-thread GDAL handles keyed by path or CRS. GDAL datasets and
// OGR coordinate transformations are not thread-safe, so every thread that produces
// raster tiles gets its own handles, opened on first use and closed when the thread
// ends. The handles are GDAL C handles (GDALDatasetH, OGRCoordinateTransformationH)
// passed as void* so this header does not pull GDAL into sylva_core's public include
// path; they are owned by the pool and valid until the calling thread exits.
//
// Failures come back as Result errors ("<path>: <reason>"), and are not cached: the
// caller (RasterSource) remembers them. GDAL's own stderr messages are silenced while
// the pool works; the reason is taken from CPLGetLastErrorMsg().
#pragma once

#include <string>

#include "sylva/core/base/Result.h"

namespace sylva {

class GdalDatasetPool {
public:
    // The calling thread's read-only dataset for `path` (GDALDatasetH).
    static Result<void*> dataset(const std::string& path);

    // The calling thread's transformation from WGS84 longitude/latitude in degrees
    // (traditional GIS axis order: x = longitude) to the CRS given as WKT, also with
    // x = easting/longitude (OGRCoordinateTransformationH).
    static Result<void*> fromLonLat(const std::string& wkt);

    // Registers GDAL's drivers once (thread-safe); every entry point calls it.
    static void registerDrivers();

    // Number of datasets open on the calling thread (for tests).
    static int openCount();
};

}  // namespace sylva
