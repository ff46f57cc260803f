#include "sylva/bench/TerrainBenchmark.h"

#include <glad/gl.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "BenchShaders.h"
#include "GridElevationSource.h"
#include "GridMesh.h"
#include "TerrainFlight.h"
#include "sylva/bench/BenchmarkMetrics.h"
#include "sylva/core/geo/Ellipsoid.h"
#include "sylva/core/image/ImageWriter.h"
#include "sylva/core/scheduler/Scheduler.h"
#include "sylva/render/gl/Framebuffer.h"
#include "sylva/render/scene/SceneRenderer.h"
#include "sylva/render/shading/ShadingPass.h"

namespace sylva::bench {

using namespace sylva::render;
// The rendered frame, not sylva::Image<Channel> (which the directive above would make
// ambiguous).
using render::Image;

namespace {

// What the clipmap flights measure (per frame of the first flight, unless noted).
struct ClipmapFlight {
    double trianglesMax[2] = {0, 0};  // of each flight: the DEM and 16x its samples
    std::vector<double> frameMs, updateMs, totalMs, terrainMs, uploadBytes;
    int framesWaiting = 0;  // frames drawn with fewer levels than wanted (tiles still coming)
    double levelsMissing = 0;
    std::vector<std::pair<double, std::pair<int, int>>> levelsPerAltitude;
};

void recordFrame(const RenderStatistics& statistics, const FlightFrame& frame, double ms,
                 ClipmapFlight& flight) {
    // The frame proper (draw, shade, read back) and, separately, the CPU clipmap
    // update: with waitForTiles it includes waiting for the workers; without, only
    // copying ready tiles (seed 001 §4.6-4.7).
    flight.frameMs.push_back(statistics.gpuSeconds * 1000.0);
    flight.updateMs.push_back(statistics.terrain.updateSeconds * 1000.0);
    flight.totalMs.push_back(ms);
    flight.terrainMs.push_back(statistics.terrainPassSeconds * 1000.0);
    flight.uploadBytes.push_back(double(statistics.terrain.uploadedBytes));
    if (statistics.terrain.waitingLevel >= 0) {
        ++flight.framesWaiting;
        flight.levelsMissing += statistics.terrain.wanted.finest - statistics.terrain.levels.finest;
    }
    flight.levelsPerAltitude.push_back(
        {frame.altitude, {statistics.terrain.levels.coarsest, statistics.terrain.levels.finest}});
}

// One clipmap flight (`pass` 0 over `grid`, 1 over 16x its samples) through a fresh
// Scheduler; the first writes its frames to options.framesFolder when set.
Status flyClipmap(SceneRenderer& renderer, const ElevationGrid& grid,
                  const std::vector<FlightFrame>& frames, const RenderSettings& settings,
                  const TerrainBenchmarkOptions& options, int pass, ClipmapFlight& flight) {
    using Clock = std::chrono::steady_clock;
    const FlightTerrain terrain(pass == 0 ? grid : upsample(grid, 4));
    SchedulerOptions schedulerOptions;
    schedulerOptions.format = TileFormat{256, 2};
    schedulerOptions.budgetBytes = options.cacheBytes;
    Scheduler evaluator(schedulerOptions);
    const TerrainLayers layers = terrain.layers();
    for (const FlightFrame& frame : frames) {
        const auto start = Clock::now();
        Result<Image> image = renderer.render(layers, evaluator, frame.camera, settings);
        if (!image) {
            return Error{"terrain benchmark: " + image.error().message};
        }
        const double ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
        const RenderStatistics& statistics = renderer.statistics();
        flight.trianglesMax[pass] =
            std::max(flight.trianglesMax[pass], double(statistics.terrain.triangles));
        if (pass == 0 && !options.framesFolder.empty()) {
            char name[32];
            std::snprintf(name, sizeof name, "flight_%03zu.png", flight.totalMs.size());
            const Status written =
                ImageWriter::writeRgba8(std::filesystem::path(options.framesFolder) / name,
                                        image->width, image->height, image->pixels);
            if (!written) {
                return written.error();
            }
        }
        if (pass == 0) {
            recordFrame(statistics, frame, ms, flight);
        }
    }
    return {};
}

// What the brute-force frames measure: the G-buffer draw alone and the whole frame
// (draw, shade, read back), milliseconds; the mesh's triangles.
struct BruteForceFlight {
    std::vector<double> drawMs, totalMs;
    double triangles = 0;
};

// The brute-force mesh of the base DEM, drawn into the same G-buffer formats and
// shaded and read back the same way, on frames sampled along the same flight.
Result<BruteForceFlight> flyBruteForce(const ShaderLibrary& library, const ElevationGrid& grid,
                                       const std::vector<FlightFrame>& frames,
                                       const RenderSettings& settings,
                                       const TerrainBenchmarkOptions& options) {
    using Clock = std::chrono::steady_clock;
    Result<GridMesh> mesh =
        GridMesh::create(withBenchShaders(library), grid,
                         Ellipsoid::toEcef({kFlightCentreLatitude, kFlightCentreLongitude, 0.0}));
    if (!mesh) {
        return mesh.error();
    }
    Result<Framebuffer> gbuffer =
        Framebuffer::create(options.width, options.height, {GL_RGBA16F, GL_RGBA16F}, true);
    Result<Framebuffer> output =
        Framebuffer::create(options.width, options.height, {GL_RGBA8}, false);
    Result<std::unique_ptr<ShadingPass>> shading = ShadingPass::create(library);
    if (!gbuffer || !output || !shading) {
        return Error{"terrain benchmark: cannot create the brute-force targets"};
    }
    BruteForceFlight flight;
    flight.triangles = double(mesh->triangles());
    for (int sample = 0; sample < options.bruteForceFrames; ++sample) {
        const FlightFrame& frame = frames[std::size_t(sample) * (frames.size() - 1) /
                                          std::max(1, options.bruteForceFrames - 1)];
        const double aboveTerrain = frame.altitude;
        const double near = std::clamp(0.3 * aboveTerrain, 0.02, 1.0e4);
        const glm::dmat4 projection = SceneRenderer::projection(
            frame.camera.verticalFov, double(options.width) / options.height, near);
        const auto start = Clock::now();
        glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
        gbuffer->bind();
        gbuffer->clearColor(0, glm::vec4(0.0f));
        gbuffer->clearColor(1, glm::vec4(0.0f));
        gbuffer->clearDepth(0.0f);
        mesh->draw(frame.camera, projection);
        glFinish();
        flight.drawMs.push_back(
            std::chrono::duration<double, std::milli>(Clock::now() - start).count());
        ShadingSettings shade;
        shade.sunDirection = settings.sunDirection;
        shade.exposure = settings.exposure;
        shading.value()->run(gbuffer.value(), output.value(), frame.camera, projection, near,
                             shade);
        (void)output->readPixelsRGBA8(0);
        glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
        flight.totalMs.push_back(
            std::chrono::duration<double, std::milli>(Clock::now() - start).count());
    }
    Framebuffer::unbind();
    return flight;
}

std::map<std::string, double> terrainMetrics(const ClipmapFlight& clipmap,
                                             const BruteForceFlight& bruteForce, std::size_t frames,
                                             const TerrainBenchmarkOptions& options) {
    std::map<std::string, double> metrics;
    metrics["ms_per_frame_median"] = median(clipmap.frameMs);
    metrics["update_ms_per_frame_median"] = median(clipmap.updateMs);
    metrics["total_ms_per_frame_median"] = median(clipmap.totalMs);
    metrics["triangles_per_frame_max"] = clipmap.trianglesMax[0];
    metrics["upload_bytes_per_frame_median"] = median(clipmap.uploadBytes);
    // The terrain methods are compared on the terrain pass (the G-buffer draw); the
    // shading pass that follows is the same per-pixel work for both.
    metrics["terrain_pass_ms_median"] = median(clipmap.terrainMs);
    metrics["bruteforce_ms_per_frame"] = median(bruteForce.drawMs);
    metrics["bruteforce_total_ms_per_frame"] = median(bruteForce.totalMs);
    metrics["bruteforce_triangles"] = bruteForce.triangles;
    metrics["speedup_vs_bruteforce"] =
        median(bruteForce.drawMs) / std::max(median(clipmap.terrainMs), 1e-9);
    metrics["triangles_growth"] = clipmap.trianglesMax[1] / std::max(clipmap.trianglesMax[0], 1.0);
    metrics["frames"] = double(frames);
    metrics["frames_waiting_for_tiles"] = clipmap.framesWaiting;
    metrics["levels_missing_per_waiting_frame"] =
        clipmap.framesWaiting ? clipmap.levelsMissing / clipmap.framesWaiting : 0.0;
    metrics["wait_for_tiles"] = options.waitForTiles ? 1 : 0;
    metrics["width"] = options.width;
    metrics["height"] = options.height;
    metrics["dem_samples"] = options.demSamples;
    return metrics;
}

}  // namespace

std::string TerrainBenchmarkResult::json() const {
    std::string text = "{\"suite\":\"terrain\",\"metrics\":{";
    text += metricsJsonMembers(MetricList(metrics.begin(), metrics.end()),
                               {NumberFormat::Notation::General, 6});
    text += ",\"levels_rendered\":[";
    char buffer[128];
    for (std::size_t i = 0; i < levelsPerAltitude.size(); ++i) {
        std::snprintf(buffer, sizeof buffer,
                      "%s{\"altitude_m\":%.6g,\"coarsest\":%d,\"finest\":%d}", i ? "," : "",
                      levelsPerAltitude[i].first, levelsPerAltitude[i].second.first,
                      levelsPerAltitude[i].second.second);
        text += buffer;
    }
    return text + "]}}";
}

Result<TerrainBenchmarkResult> runTerrainBenchmark(const ShaderLibrary& library,
                                                   const TerrainBenchmarkOptions& options) {
    const ElevationGrid grid = makeFlightDem(options.demSamples, options.demDegrees);
    const std::vector<FlightFrame> frames = terrainFlight(grid, options.framesPerSegment);
    Result<std::unique_ptr<SceneRenderer>> created =
        SceneRenderer::create(library, TerrainSettings{});
    if (!created) {
        return created.error();
    }
    RenderSettings settings = flightRenderSettings(options.width, options.height);
    settings.waitForTiles = options.waitForTiles;
    // The clipmap flight, twice: over the DEM, and over 16x its samples.
    ClipmapFlight clipmap;
    for (int pass = 0; pass < 2; ++pass) {
        if (Status flown =
                flyClipmap(*created.value(), grid, frames, settings, options, pass, clipmap);
            !flown) {
            return flown.error();
        }
    }
    Result<BruteForceFlight> bruteForce = flyBruteForce(library, grid, frames, settings, options);
    if (!bruteForce) {
        return bruteForce.error();
    }
    TerrainBenchmarkResult result;
    result.metrics = terrainMetrics(clipmap, bruteForce.value(), frames.size(), options);
    result.levelsPerAltitude = std::move(clipmap.levelsPerAltitude);
    return result;
}

}  // namespace sylva::bench
