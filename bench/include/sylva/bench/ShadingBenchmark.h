// ShadingBenchmark: `sylva bench shading`, the costs of the shading features of issue 16
// on the terrain benchmark's flight and the vegetation benchmark's forest at 1280×720.
// Each feature measures in a function of its own (bench/ShadowBenchmark.h: sun shadows,
// key `shadow_frame_ratio`, and screen-space ambient occlusion on the same frames, key
// `ssao_frame_ratio`), so features add their keys to the one suite.
//
// Needs a current GL 4.5 context. The forest's plant (a generated oak with its LoD and
// billboard clouds) is built at the start, which takes a while and is not timed.
#pragma once

#include <map>
#include <string>

#include "sylva/core/base/Result.h"
#include "sylva/render/gl/ShaderLibrary.h"

namespace sylva::bench {

struct ShadingBenchmarkOptions {
    int width = 1280;
    int height = 720;
    int flightFramesPerSegment = 2;  // terrain flight: 4 segments (9 frames)
    int demSamples = 1024;           // per side of the flight's DEM (the terrain bench: 4096)
    int forestFramesPerSegment = 2;  // forest path: 4 segments (9 frames)
    int trees = 10000;
    int leaves = 1000;  // of the generated oak
    // Moving camera (bench/ShadowBenchmark.h): timed frames per stretch (0: none) and the
    // cascades' re-centring margin (ShadowSettings::recentreMargin; negative: the default).
    int movingFrames = 24;
    double shadowMargin = -1.0;
};

struct ShadingBenchmarkResult {
    std::map<std::string, double> metrics;
    std::string json() const;  // {"suite":"shading","metrics":{...}}
};

Result<ShadingBenchmarkResult> runShadingBenchmark(const render::ShaderLibrary& library,
                                                   const ShadingBenchmarkOptions& options);

}  // namespace sylva::bench
