#include "sylva/bench/AntiAliasingBenchmark.h"
#include "sylva/bench/BenchmarkMetrics.h"

#include <algorithm>
#include <memory>
#include <vector>

#include "TerrainFlight.h"
#include "sylva/core/scheduler/Scheduler.h"
#include "sylva/render/scene/SceneRenderer.h"

namespace sylva::bench {

Result<AntiAliasingBenchmarkResult> runAntiAliasingBenchmark(
    const render::ShaderLibrary& library, const AntiAliasingBenchmarkOptions& options) {
    const ElevationGrid grid = makeFlightDem(options.demSamples, 4.0);
    const std::vector<FlightFrame> frames = terrainFlight(grid, options.framesPerSegment);
    const FlightTerrain terrain(grid);
    Result<std::unique_ptr<render::SceneRenderer>> renderer =
        render::SceneRenderer::create(library, render::TerrainSettings{});
    if (!renderer) {
        return renderer.error();
    }
    SchedulerOptions schedulerOptions;
    schedulerOptions.format = TileFormat{256, 2};
    schedulerOptions.budgetBytes = std::size_t(512) << 20;
    Scheduler scheduler(schedulerOptions);
    render::RenderSettings settings = flightRenderSettings(options.width, options.height);
    settings.waitForTiles = true;
    std::vector<double> singleMs, multipleMs;
    for (const FlightFrame& frame : frames) {
        // The single-sample frame first: it also brings the frame's tiles in, so neither
        // timed render waits for the workers.
        for (int samples : {1, options.samples}) {
            settings.samples = samples;
            Result<render::Image> image =
                renderer.value()->render(terrain.layers(), scheduler, frame.camera, settings);
            if (!image) {
                return Error{"anti-aliasing benchmark: " + image.error().message};
            }
            (samples == 1 ? singleMs : multipleMs)
                .push_back(renderer.value()->statistics().gpuSeconds * 1000.0);
        }
    }
    AntiAliasingBenchmarkResult result;
    const double single = median(singleMs), multiple = median(multipleMs);
    result.metrics["aa4_frame_ratio"] = multiple / std::max(single, 1e-9);
    result.metrics["aa1_ms_median"] = single;
    result.metrics["aa4_ms_median"] = multiple;
    result.metrics["aa_frames"] = double(frames.size());
    return result;
}

}  // namespace sylva::bench
