// ViewerBenchmark: `sylva bench viewer`, the interactive viewer (render::Viewer) on a
// scripted flight over Olinda (data/olinda, scripts/fetch-samples), headless: the
// `space` camera, the `aircraft` camera and a descent towards the forest, then the
// `ground` camera walking into the forest, then standing still. Interactive frames use
// the frame budget (`--budget-ms`, FrameBudget); the metrics:
//  - frame_ms_p50, frame_ms_p95: milliseconds of the render call (update, draw,
//    read-back) over every interactive frame of the flight and the still period;
//  - budget_overrun_p95: frame_ms_p95 / budget;
//  - frames_with_holes: frames with a pixel that shows sky (depth 0) although its view
//    ray passes 50 m or more under the ellipsoid's surface beyond twice the near plane:
//    the terrain failed to cover it (grazing rays at the horizon and the limb, where the
//    ring mesh's chords rightly let the sky through, are not counted);
//  - seconds_to_full_detail_after_stop: from the end of the last moving frame to the
//    first frame with nothing pending (terrain and canopy levels, instance tiles, plant
//    assets, the nadir height) and the budget level it then keeps; the still frames go
//    on after `stillFrames` until nothing is pending (wait-tiles, at most 600 s);
//  - quality_oscillations: budget level reversals per second over the still frames.
#pragma once

#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>

#include "sylva/bench/BenchmarkMetrics.h"
#include "sylva/core/base/Result.h"

namespace sylva::bench {

struct ViewerBenchmarkOptions {
    std::filesystem::path project = "projects/olinda/olinda.sylva";
    int width = 1280;
    int height = 720;
    double budgetMilliseconds = 250;
    int flightSteps = 12;   // frames per leg of the flight (descent, walk)
    int stillFrames = 30;   // frames after the stop (then on until full detail)
    FILE* trace = nullptr;  // one line per frame (time, ms, pending, levels, holes) if set
    // The disk tile cache's folder (as `sylva view --disk-cache`); none: every tile is
    // produced (a cold start). A second run with the same folder measures a warm one.
    std::optional<std::filesystem::path> diskCache;
};

struct ViewerBenchmarkResult {
    MetricList metrics;        // in the order above
    std::string json() const;  // {"suite":"viewer","metrics":{...}}
};

// Fails when the project is missing or has errors, or the viewer fails.
Result<ViewerBenchmarkResult> runViewerBenchmark(const ViewerBenchmarkOptions& options);

}  // namespace sylva::bench
