// AntiAliasingBenchmark: the anti-aliasing part of `sylva bench shading`. The terrain
// bench flight (bench/TerrainFlight.h) at width × height, every frame rendered with 1 and
// with `samples` samples per pixel (SampleAccumulator); tiles are complete before a frame
// is timed (waitForTiles), and the time is the frame proper (draw, shade, accumulate,
// read back: RenderStatistics::gpuSeconds), so only the sampling differs.
// Metrics: aa4_frame_ratio (median frame time with `samples` / median with 1; the key
// names 4 samples, the default), aa1_ms_median, aa4_ms_median, aa_frames.
// Needs a current GL 4.5 context; errors are render errors (Result).
#pragma once

#include <map>
#include <string>

#include "sylva/core/base/Result.h"
#include "sylva/render/gl/ShaderLibrary.h"

namespace sylva::bench {

struct AntiAliasingBenchmarkOptions {
    int width = 1280;
    int height = 720;
    int samples = 4;
    int demSamples = 2048;     // per side of the flight's DEM
    int framesPerSegment = 2;  // frames between successive altitudes of the flight
};

struct AntiAliasingBenchmarkResult {
    std::map<std::string, double> metrics;
};

Result<AntiAliasingBenchmarkResult> runAntiAliasingBenchmark(
    const render::ShaderLibrary& library, const AntiAliasingBenchmarkOptions& options);

}  // namespace sylva::bench
