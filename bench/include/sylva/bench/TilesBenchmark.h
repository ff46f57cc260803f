// TilesBenchmark: `sylva bench tiles`, the tile pipeline on the Olinda sample data
// (scripts/fetch-samples: DATA/olinda/olinda_dem_utm25s.tif and L7_ETMs.tif):
//  - peak_rss_mb / budget_mb: a long run of the reference chain over ~1,500 distinct
//    tiles with the Scheduler's cache budget (run first, so the process's peak RSS,
//    VmHWM, belongs to it; MiB above the resident set before the run);
//  - tiles_per_s_1_worker / _2_workers / worker_scaling: the reference chain, cold
//    caches, every 256² tile over the DEM at level 14 (best of three, interleaved);
//  - sylva_reprojection_tiles_per_s / gdal_tiles_per_s: the DEM reprojected to the
//    same lon/lat tiles (bilinear, 2-texel border) by the raster source and by GDAL's
//    in-process warper (GDALCreateGenImgProjTransformer2 + approximate transformer at
//    0.125 pixels, as gdalwarp's default, + GDALWarpOperation into a MEM dataset), one
//    thread each;
//  - update_bytes_ratio: bytes of clipmap region updates along a scripted slow flight
//    divided by the bytes of rebuilding every level each frame (CPU Clipmaps only).
//
// The reference chain per tile key: DEM (raster, UTM 25S) blended over a constant
// base (blend, elevation, using the DEM's coverage) → normal_map; and the Landsat
// scene (raster, bands 3-2-1) → adjust. `adjust` only takes images, so the image
// branch carries it; a "tile" here is one key with both outputs. CPU only.
#pragma once

#include <cstddef>
#include <filesystem>
#include <map>
#include <string>

#include "sylva/core/base/Result.h"

namespace sylva::bench {

struct TilesBenchmarkOptions {
    std::filesystem::path dataFolder = "data";  // holds olinda/ of scripts/fetch-samples
    std::size_t budgetMegabytes = 64;           // the cache budget of the peak-RSS run, MiB
    bool verbose = false;  // resident sets and per-source statistics of every run on stderr
};

struct TilesBenchmarkResult {
    std::map<std::string, double> metrics;
    std::string json() const;  // {"suite":"tiles","metrics":{...}}, %.6g, keys sorted
};

// Fails when a sample file is missing ("sample file '...' is missing; run
// scripts/fetch-samples (or give --data DIR)"), cannot be opened, or a tile fails.
Result<TilesBenchmarkResult> runTilesBenchmark(const TilesBenchmarkOptions& options);

}  // namespace sylva::bench
