// ViewerBenchmark: `sylva bench viewer`, the interactive viewer (render::Viewer) on a
// scripted flight over Olinda (data/olinda, scripts/fetch-samples), headless: the
// `space` camera, the `aircraft` camera and a descent towards the forest, then the
// `ground` camera walking into the forest, then standing still. Interactive frames use
// the frame budget (`--budget-ms`, FrameBudget); the metrics:
//  - frame_ms_p50, frame_ms_p95: milliseconds of the render call (update, draw,
//    read-back) over every interactive frame of the flight and the still period;
//  - budget_overrun_p95: frame_ms_p95 / budget;
//  - frames_with_holes: frames with a pixel whose view ray meets the ellipsoid (beyond
//    twice the near plane) but shows sky (depth 0): the terrain failed to cover it;
//  - seconds_to_full_detail_after_stop: from the end of the last moving frame to the
//    first frame with no tile pending and the budget level it then keeps;
//  - quality_oscillations: budget level reversals per second over the still frames.
#pragma once

#include <filesystem>
#include <string>

#include "sylva/bench/BenchmarkMetrics.h"
#include "sylva/core/base/Result.h"

namespace sylva::bench {

struct ViewerBenchmarkOptions {
    std::filesystem::path project = "projects/olinda/olinda.sylva";
    int width = 1280;
    int height = 720;
    double budgetMilliseconds = 250;
    int flightSteps = 12;  // frames per leg of the flight (descent, walk)
    int stillFrames = 30;  // frames after the stop
};

struct ViewerBenchmarkResult {
    MetricList metrics;        // in the order above
    std::string json() const;  // {"suite":"viewer","metrics":{...}}
};

// Fails when the project is missing or has errors, or the viewer fails.
Result<ViewerBenchmarkResult> runViewerBenchmark(const ViewerBenchmarkOptions& options);

}  // namespace sylva::bench
