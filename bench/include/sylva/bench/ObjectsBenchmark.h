// ObjectsBenchmark: `sylva bench objects`. The terrain benchmark's flight (800 km down to
// 50 m, approaching (46° N, 8° E) from the south; the same noise relief, evaluated
// directly instead of through a DEM grid) rendered with a generated city of extruded
// footprints and with a wind farm of instanced turbines around the flight's end, against
// the same frames with the terrain alone.
//
// Metrics: buildings_frame_ratio and turbines_frame_ratio (median frame time with the
// city / with the farm over the median with the terrain alone; frames after a warm-up
// pass, so tile production and mesh building are not timed), buildings_build_s_100k
// (footprints to drawable tiles: checking every footprint, then building every tile's
// triangles on the CPU, scaled to 100,000 buildings when fewer are asked for),
// buildings_triangles (of the whole city). Needs a current GL 4.5 context.
#pragma once

#include <cstddef>
#include <string>

#include "sylva/bench/BenchmarkMetrics.h"
#include "sylva/core/base/Result.h"
#include "sylva/render/gl/ShaderLibrary.h"

namespace sylva::bench {

struct ObjectsBenchmarkOptions {
    int width = 1280;
    int height = 720;
    int buildings = 100000;
    int turbines = 1000;
    int framesPerSegment = 4;  // frames between successive altitudes of the flight
    std::size_t cacheMegabytes =
        1024;  // the Scheduler's tile budget (SchedulerOptions::budgetBytes)
};

struct ObjectsBenchmarkResult {
    MetricList metrics;
    std::string json() const;  // {"suite":"objects","metrics":{...}}
};

Result<ObjectsBenchmarkResult> runObjectsBenchmark(const render::ShaderLibrary& library,
                                                   const ObjectsBenchmarkOptions& options);

}  // namespace sylva::bench
