// AtmosphereBenchmark: the atmosphere's part of `sylva bench shading`. Along the terrain
// bench's flight (800 km to 50 m over a 4-degree DEM at 46 N 8 E, looking down from space
// and towards the horizon near the ground; here the brute-force grid mesh of a smooth
// synthetic DEM draws the G-buffer, as the atmosphere's cost depends only on which pixels
// are sky or ground and how far), per frame at 1280x720:
//  - atmosphere_ms_median: the LUT atmosphere's share of the frame, milliseconds: the
//    shading pass with the atmosphere (sky-view LUT + aerial-perspective volume computed
//    for the frame, then the per-pixel look-ups) minus the same pass without sky and haze;
//  - atmosphere_legacy_ms_median: the same for the former per-pixel single-scattering
//    ray march (bench/shaders/legacy_shade.frag, kept only for this measurement);
//  - atmosphere_speedup: median over frames of legacy / LUT milliseconds.
// Each pass is timed to glFinish; the better of two runs per frame counts.
#pragma once

#include <string>

#include "sylva/bench/BenchmarkMetrics.h"
#include "sylva/core/base/Result.h"
#include "sylva/render/gl/ShaderLibrary.h"

namespace sylva::bench {

struct AtmosphereBenchmarkOptions {
    int width = 1280;
    int height = 720;
    int framesPerSegment = 3;  // frames between successive altitudes of the flight
};

struct AtmosphereBenchmarkResult {
    MetricList metrics;
    std::string json() const;  // {"suite":"shading","metrics":{...}}
};

// Needs a current GL 4.5 context. Fails if a shader does not build.
Result<AtmosphereBenchmarkResult> runAtmosphereBenchmark(const render::ShaderLibrary& library,
                                                         const AtmosphereBenchmarkOptions& options);

}  // namespace sylva::bench
