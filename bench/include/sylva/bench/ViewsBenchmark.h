// ViewsBenchmark: `sylva bench views`, verified views (issue 18) on the synthetic marker
// fixture (bench/MarkerFixture: flat ground at 100 m with surveyed markers, atmosphere
// off, camera 250 m above the ground, tiles warmed by one render first):
//  - planar_ms_per_mpx: wall milliseconds per megapixel of a planar 53.5° image
//    (PanoramaRenderer, i.e. SceneRenderer directly), best of `repeats` (the two
//    cameras' renders alternate, so load changes hit both alike);
//  - cylindrical_ms_per_mpx: the same for a 90° cylindrical panorama of the same pixel
//    size (2 strips of 45° rendered and resampled per pixel);
//  - cylindrical_cost_ratio: the ratio of the two (target ≤ 1.5);
//  - match_ms: one CameraMatcher solve of heading, pitch and roll from 8 control points
//    (the marker centroids detected in a rendered 640 × 360 "photograph", first guess 3°
//    off), best of `repeats` × 10;
//  - control_point_rms_px: that solve's rms residual (no noise added: the centroids'
//    own error against the exact camera model; target ≤ 0.5).
#pragma once

#include <string>

#include "sylva/bench/BenchmarkMetrics.h"
#include "sylva/core/base/Result.h"

namespace sylva::bench {

struct ViewsBenchmarkOptions {
    int width = 1280;  // both images
    int height = 406;  // NatureScot's 820 x 260 mm aspect
    int repeats = 5;
};

struct ViewsBenchmarkResult {
    MetricList metrics;        // in the order above
    std::string json() const;  // {"suite":"views","metrics":{...}}
};

// Fails when no GL context can be made or a render or the match fails.
Result<ViewsBenchmarkResult> runViewsBenchmark(const ViewsBenchmarkOptions& options);

}  // namespace sylva::bench
