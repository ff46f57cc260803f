#include "sylva/bench/TerrainBenchmark.h"

#include <glad/gl.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>

#include "BenchShaders.h"
#include "GridElevationSource.h"
#include "GridMesh.h"
#include "sylva/bench/BenchmarkMetrics.h"
#include "sylva/core/base/WorkerPool.h"
#include "sylva/core/geo/Ellipsoid.h"
#include "sylva/core/image/ImageWriter.h"
#include "sylva/core/scheduler/Scheduler.h"
#include "sylva/core/sources/raster/HypsometricSource.h"
#include "sylva/core/sources/raster/NoiseSource.h"
#include "sylva/core/sources/raster/NormalMapSource.h"
#include "sylva/render/gl/Framebuffer.h"
#include "sylva/render/scene/SceneRenderer.h"
#include "sylva/render/shading/ShadingPass.h"

namespace sylva::bench {

using namespace sylva::render;
// The rendered frame, not sylva::Image<Channel> (which the directive above would make
// ambiguous).
using render::Image;

namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
constexpr double kCentreLatitude = 46.0 * kDegree;
constexpr double kCentreLongitude = 8.0 * kDegree;
// Altitudes above the ground of seed 001 Table 4.1, metres.
constexpr double kAltitudes[] = {800e3, 100e3, 10e3, 1e3, 50.0};

double median(std::vector<double> values) {
    if (values.empty()) {
        return 0.0;
    }
    std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
    return values[values.size() / 2];
}

ElevationGrid makeDem(int samples, double degrees) {
    NoiseParameters parameters;  // the demo project's relief
    parameters.seed = 7;
    parameters.amplitude = 3000;
    parameters.baseWavelength = 3.0e6;
    parameters.ridges = 0.6;
    parameters.ridgeWavelength = 3.0e5;
    parameters.roughness = 0.7;
    const NoiseSource noise("dem", parameters);
    ElevationGrid grid;
    grid.width = grid.height = samples;
    grid.west = kCentreLongitude - degrees / 2 * kDegree;
    grid.east = kCentreLongitude + degrees / 2 * kDegree;
    grid.south = kCentreLatitude - degrees / 2 * kDegree;
    grid.north = kCentreLatitude + degrees / 2 * kDegree;
    grid.heights.resize(std::size_t(samples) * samples);
    const double footprint = grid.sampleSpacingLatitude() * Ellipsoid::kMeanRadius;
    WorkerPool::shared().run(samples, [&](int row) {
        const double latitude = grid.north - row * grid.sampleSpacingLatitude();
        for (int column = 0; column < samples; ++column) {
            const double longitude = grid.west + column * grid.sampleSpacingLongitude();
            const glm::dvec3 direction = Ellipsoid::surfaceNormal(latitude, longitude);
            grid.heights[std::size_t(row) * samples + column] =
                float(noise.height(direction, footprint));
        }
    });
    return grid;
}

// The same surface with `factor` times the samples per side (bilinear), i.e. a DEM
// with factor^2 the data.
ElevationGrid upsample(const ElevationGrid& grid, int factor) {
    ElevationGrid fine = grid;
    fine.width = (grid.width - 1) * factor + 1;
    fine.height = (grid.height - 1) * factor + 1;
    fine.heights.assign(std::size_t(fine.width) * fine.height, 0.0f);
    WorkerPool::shared().run(fine.height, [&](int row) {
        const double latitude = fine.north - row * fine.sampleSpacingLatitude();
        for (int column = 0; column < fine.width; ++column) {
            fine.heights[std::size_t(row) * fine.width + column] =
                float(grid.at(latitude, fine.west + column * fine.sampleSpacingLongitude(), 0.0));
        }
    });
    return fine;
}

struct FlightFrame {
    Camera camera;
    double altitude;
};

std::vector<FlightFrame> flight(const ElevationGrid& grid, int framesPerSegment) {
    std::vector<FlightFrame> frames;
    const int segments = int(std::size(kAltitudes)) - 1;
    const int total = segments * framesPerSegment + 1;
    for (int frame = 0; frame < total; ++frame) {
        const double progress = double(frame) / (total - 1);
        const int segment = std::min(frame / framesPerSegment, segments - 1);
        const double local = double(frame - segment * framesPerSegment) / framesPerSegment;
        const double altitude = std::exp(std::log(kAltitudes[segment]) * (1 - local) +
                                         std::log(kAltitudes[segment + 1]) * local);
        // Approach the DEM centre from the south while descending; look down from
        // space, towards the horizon near the ground.
        const double latitude = kCentreLatitude - 0.6 * kDegree * (1 - progress);
        const double longitude = kCentreLongitude + 0.2 * kDegree * (1 - progress);
        const double pitch = (-85.0 + 75.0 * std::pow(progress, 0.7)) * kDegree;
        Camera camera;
        camera.geodetic = {latitude, longitude, grid.at(latitude, longitude, 0.0) + altitude};
        camera.position = Ellipsoid::toEcef(camera.geodetic);
        camera.axes = Camera::axesFromAngles(camera.geodetic, 10 * kDegree, pitch, 0.0);
        camera.verticalFov = 60 * kDegree;
        frames.push_back({camera, altitude});
    }
    return frames;
}

// The frame settings of both flights: the demo project's sun and exposure, no ocean.
RenderSettings flightSettings(const TerrainBenchmarkOptions& options) {
    RenderSettings settings;
    settings.width = options.width;
    settings.height = options.height;
    settings.ocean = false;
    settings.sunDirection = Ellipsoid::surfaceNormal(5 * kDegree, -40 * kDegree);
    settings.exposure = 0.45;  // as the demo project
    settings.waitForTiles = options.waitForTiles;
    return settings;
}

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
    const GridElevationSource elevation("dem", pass == 0 ? grid : upsample(grid, 4), 0.0);
    const NormalMapSource normals("dem.normals", &elevation, 1.0);
    HypsometricParameters colours;  // the schema's defaults, linear RGB
    colours.water = {0.0056f, 0.0194f, 0.0742f};
    colours.shallowWater = {0.0100f, 0.0844f, 0.1470f};
    colours.rock = {0.1470f, 0.1274f, 0.1000f};
    const HypsometricSource colour("dem.colour", &elevation, &normals, colours);
    SchedulerOptions schedulerOptions;
    schedulerOptions.format = TileFormat{256, 2};
    schedulerOptions.budgetBytes = options.cacheBytes;
    Scheduler evaluator(schedulerOptions);
    const TerrainLayers layers{&elevation, &colour, &normals, {}, {}};
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
                         Ellipsoid::toEcef({kCentreLatitude, kCentreLongitude, 0.0}));
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
    const ElevationGrid grid = makeDem(options.demSamples, options.demDegrees);
    const std::vector<FlightFrame> frames = flight(grid, options.framesPerSegment);
    Result<std::unique_ptr<SceneRenderer>> created =
        SceneRenderer::create(library, TerrainSettings{});
    if (!created) {
        return created.error();
    }
    const RenderSettings settings = flightSettings(options);
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
