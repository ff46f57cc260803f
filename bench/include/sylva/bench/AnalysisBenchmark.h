// AnalysisBenchmark: `sylva bench analysis`, the bare-earth ZTV (core/analysis) against
// GDAL's viewshed on the Olinda DEM (data/olinda, scripts/fetch-samples) resampled
// bilinearly to `resolution` (default 30 m: 333² cells), target 120 m on the DEM's
// highest cell, observer 2 m, k = 0.13:
//  - ztv_cells_per_s: cells per second of wall time of computeViewshed (WorkerPool over
//    rows, all hardware threads), one target;
//  - gdal_viewshed_cells_per_s: the same for GDALViewshedGenerate (libgdal, GVM_Edge as
//    gdal_viewshed uses, MEM output, one thread) with its observer at the target;
//  - ztv_speed_vs_gdal: the ratio of the two rates;
//  - ztv_agreement_gdal: share of cells whose visibility agrees;
//  - cumulative_ztv_20_targets_s: seconds for 20 targets (seeded random cells, 150 m).
// Each timing is the best of `repeats` runs.
#pragma once

#include <filesystem>
#include <string>

#include "sylva/bench/BenchmarkMetrics.h"
#include "sylva/core/base/Result.h"

namespace sylva::bench {

struct AnalysisBenchmarkOptions {
    std::filesystem::path dataFolder = "data";
    double resolution = 30.0;  // metres
    int repeats = 3;
};

struct AnalysisBenchmarkResult {
    MetricList metrics;        // in the order above
    std::string json() const;  // {"suite":"analysis","metrics":{...}}
};

// Fails when the DEM is absent ("... run scripts/fetch-samples") or GDAL fails.
Result<AnalysisBenchmarkResult> runAnalysisBenchmark(const AnalysisBenchmarkOptions& options);

}  // namespace sylva::bench
