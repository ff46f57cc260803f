#include "ShadowBenchmark.h"
#include "sylva/bench/BenchmarkMetrics.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <utility>
#include <vector>

#include "BenchForest.h"
#include "TerrainFlight.h"
#include "sylva/core/geo/Ellipsoid.h"
#include "sylva/core/plantlod/ShadowThresholds.h"
#include "sylva/core/scheduler/TileEvaluator.h"
#include "sylva/core/sources/raster/ConstantSource.h"
#include "sylva/core/sources/raster/HypsometricSource.h"
#include "sylva/core/sources/raster/NormalMapSource.h"
#include "sylva/render/scene/SceneRenderer.h"

namespace sylva::bench {

using namespace sylva::render;

namespace {

// Frame times of one scene, milliseconds: with and without shadows (both without SSAO),
// and with shadows and SSAO.
struct ShadowSamples {
    std::vector<double> with, without, shadowPass, withOcclusion, occlusionPass;
    double thresholdsMs = 0.0;  // ShadowThresholds of the oak (addSpecies computes them)
};

// Frame times of one scene along its moving stretches (no warm-up at each camera).
struct MovingSamples {
    std::vector<double> with, without, shadowPass;
    int cascades = 0;  // cascade draws of the timed frames with shadows
    int redrawn = 0;   // of which drawn, not copied from the cache
};

// A stretch of consecutive cameras a small step apart (a walk, a flight).
using Stretch = std::vector<Camera>;

// One camera: a warm-up render (tiles, plants), then with and without shadows, then with
// shadows and screen-space ambient occlusion.
Status measureFrame(SceneRenderer& renderer, const TerrainLayers& layers, TileProvider& provider,
                    const Camera& camera, RenderSettings settings, ShadowSamples& samples) {
    settings.shadows.enabled = true;
    if (Result<Image> warm = renderer.render(layers, provider, camera, settings); !warm) {
        return warm.error();
    }
    struct Variant {
        bool shadows, occlusion;
        std::vector<double>* frames;
    };
    for (const Variant& variant :
         {Variant{true, false, &samples.with}, Variant{false, false, &samples.without},
          Variant{true, true, &samples.withOcclusion}}) {
        settings.shadows.enabled = variant.shadows;
        settings.ambientOcclusion.enabled = variant.occlusion;
        if (Result<Image> image = renderer.render(layers, provider, camera, settings); !image) {
            return image.error();
        }
        const RenderStatistics& statistics = renderer.statistics();
        variant.frames->push_back(statistics.gpuSeconds * 1000.0);
        if (variant.shadows && !variant.occlusion) {
            samples.shadowPass.push_back(statistics.shadowPassSeconds * 1000.0);
        }
        if (variant.occlusion) {
            samples.occlusionPass.push_back(statistics.ambientOcclusionPassSeconds * 1000.0);
        }
    }
    return {};
}

// One stretch with a moving camera: a warm-up render with shadows at every camera (tiles
// and plants resident, waitForTiles), then the first camera again (the cache holds its
// boxes, as after the frame before in a real sequence), then every further camera once
// with and once without shadows, in order: no warm-up at a frame's own camera, so its
// shadow maps hold what the previous camera left (cache hits only where the cascade's
// box and the casters' keys did not change).
Status measureStretch(SceneRenderer& renderer, const TerrainLayers& layers, TileProvider& provider,
                      const Stretch& stretch, RenderSettings settings, MovingSamples& samples) {
    settings.shadows.enabled = true;
    settings.ambientOcclusion.enabled = false;
    for (std::size_t i = 0; i <= stretch.size(); ++i) {
        const Camera& camera = stretch[i < stretch.size() ? i : 0];
        if (Result<Image> warm = renderer.render(layers, provider, camera, settings); !warm) {
            return warm.error();
        }
    }
    for (std::size_t i = 1; i < stretch.size(); ++i) {
        for (const bool shadows : {true, false}) {
            settings.shadows.enabled = shadows;
            if (Result<Image> image = renderer.render(layers, provider, stretch[i], settings);
                !image) {
                return image.error();
            }
            const RenderStatistics& statistics = renderer.statistics();
            (shadows ? samples.with : samples.without).push_back(statistics.gpuSeconds * 1000.0);
            if (shadows) {
                samples.shadowPass.push_back(statistics.shadowPassSeconds * 1000.0);
                const int cascades = int(renderer.shadowMaps().cascades().size());
                samples.cascades += cascades;
                samples.redrawn += cascades - renderer.shadowMaps().cachedCascades();
            }
        }
    }
    return {};
}

// The flight's moving stretches: from the flight's frames at 1 km and at 50 m above the
// DEM, level flight (the same height above the DEM) along the flight's heading at 3 m
// (an aircraft at 90 m/s) and 0.5 m (a drone at 15 m/s) per frame of 1/30 s.
std::vector<Stretch> flightStretches(const ElevationGrid& grid, int frames) {
    std::vector<Stretch> stretches;
    for (const auto& [altitude, step] : {std::pair{1000.0, 3.0}, std::pair{50.0, 0.5}}) {
        // The flight's camera at this altitude: its last frame has 50 m; 4 frames per
        // segment put 1 km at frame 12 of 17.
        const std::vector<FlightFrame> flight = terrainFlight(grid, 4);
        const FlightFrame& key = altitude > 100.0 ? flight[12] : flight.back();
        Stretch stretch;
        const glm::dmat3 local =
            Ellipsoid::localFrame(key.camera.geodetic.latitude, key.camera.geodetic.longitude);
        // The heading: the view axis (-z) on the local horizontal plane.
        glm::dvec3 forward = -key.camera.axes[2];
        forward -= local[2] * glm::dot(forward, local[2]);
        forward = glm::normalize(forward);
        for (int i = 0; i < frames; ++i) {
            Camera camera = key.camera;
            Geodetic at = Ellipsoid::toGeodetic(key.camera.position + forward * (step * i));
            at.height = grid.at(at.latitude, at.longitude, 0.0) + key.altitude;
            camera.geodetic = at;
            camera.position = Ellipsoid::toEcef(at);  // the axes stay: a level flight
            stretch.push_back(camera);
        }
        stretches.push_back(std::move(stretch));
    }
    return stretches;
}

// The forest's moving stretches on its path (BenchForest): walking in from the forest edge
// (10 cm per frame, 3 m/s, descending with the path) and turning round inside (1° per frame).
std::vector<Stretch> forestStretches(int frames) {
    const double edge = 2.5;  // path time: halfway from the edge (160 m out) to inside
    const double segment = std::hypot(kForestPath[3].north - kForestPath[2].north,
                                      kForestPath[3].east - kForestPath[2].east);
    const double turnPerUnit = std::abs(kForestPath[4].heading - kForestPath[3].heading);
    Stretch walk, turn;
    for (int i = 0; i < frames; ++i) {
        walk.push_back(forestCamera(kForestPath, edge + i * 0.1 / segment));
        turn.push_back(forestCamera(kForestPath, 3.0 + i * (std::numbers::pi / 180) / turnPerUnit));
    }
    return {walk, turn};
}

Status measureFlight(const ShaderLibrary& library, const ShadingBenchmarkOptions& options,
                     ShadowSamples& samples, MovingSamples& moving) {
    std::fprintf(stderr, "bench shading: shadows on the terrain flight\n");
    const ElevationGrid grid = makeFlightDem(options.demSamples, 4.0);
    const FlightTerrain terrain(grid);
    TileEvaluator evaluator(TileFormat{256, 2});
    const TerrainLayers layers = terrain.layers();
    Result<std::unique_ptr<SceneRenderer>> renderer =
        SceneRenderer::create(library, TerrainSettings{});
    if (!renderer) {
        return renderer.error();
    }
    RenderSettings settings = flightRenderSettings(options.width, options.height);
    settings.waitForTiles = true;
    if (options.shadowMargin >= 0.0) {
        settings.shadows.recentreMargin = options.shadowMargin;
    }
    for (const FlightFrame& frame : terrainFlight(grid, options.flightFramesPerSegment)) {
        if (Status measured =
                measureFrame(*renderer.value(), layers, evaluator, frame.camera, settings, samples);
            !measured) {
            return measured;
        }
    }
    if (options.movingFrames > 1) {
        std::fprintf(stderr, "bench shading: shadows on the flight, moving camera\n");
    }
    for (const Stretch& stretch : options.movingFrames > 1
                                      ? flightStretches(grid, options.movingFrames)
                                      : std::vector<Stretch>{}) {
        if (Status measured =
                measureStretch(*renderer.value(), layers, evaluator, stretch, settings, moving);
            !measured) {
            return measured;
        }
    }
    return {};
}

Status measureForest(const ShaderLibrary& library, const ShadingBenchmarkOptions& options,
                     ShadowSamples& samples, MovingSamples& moving) {
    std::fprintf(stderr, "bench shading: building the oak for the forest (not timed)\n");
    Result<std::shared_ptr<PlantAsset>> asset = buildOak(options.leaves);
    if (!asset) {
        return asset.error();
    }
    const auto thresholdsStart = std::chrono::steady_clock::now();
    (void)shadowThresholds(asset.value()->model, asset.value()->lod);
    samples.thresholdsMs = std::chrono::duration<double, std::milli>(
                               std::chrono::steady_clock::now() - thresholdsStart)
                               .count();
    Result<std::unique_ptr<SceneRenderer>> renderer =
        SceneRenderer::create(library, TerrainSettings{});
    if (!renderer) {
        return renderer.error();
    }
    Result<std::uint32_t> species = renderer.value()->vegetation().addSpecies(asset.value());
    if (!species) {
        return species.error();
    }
    const std::vector<InstanceBatch> forest =
        makeForest(options.trees, species.value(), renderer.value()->vegetation().speciesLods(), 7);
    const ConstantSource elevation("flat", kForestGround);
    const ConstantSource colour("meadow", glm::vec4(0.10f, 0.14f, 0.05f, 1.0f));
    const NormalMapSource normals("flat.normals", &elevation, 1.0);
    const TerrainLayers layers{&elevation, &colour, &normals, {}, {}};
    TileEvaluator evaluator(TileFormat{256, 2});
    RenderSettings settings;  // as the vegetation benchmark
    settings.width = options.width;
    settings.height = options.height;
    settings.sunDirection =
        glm::normalize(Ellipsoid::surfaceNormal(kForestLatitude - 0.5, kForestLongitude - 0.6));
    settings.ocean = false;
    settings.instanceBatches = pointers(forest);
    if (options.shadowMargin >= 0.0) {
        settings.shadows.recentreMargin = options.shadowMargin;
    }
    std::fprintf(stderr, "bench shading: shadows in the forest\n");
    const int segments = int(kForestPath.size()) - 1;
    const int frames = segments * options.forestFramesPerSegment + 1;
    for (int frame = 0; frame < frames; ++frame) {
        const double t = double(frame) / options.forestFramesPerSegment;
        if (Status measured = measureFrame(*renderer.value(), layers, evaluator,
                                           forestCamera(kForestPath, t), settings, samples);
            !measured) {
            return measured;
        }
    }
    if (options.movingFrames > 1) {
        std::fprintf(stderr, "bench shading: shadows in the forest, moving camera\n");
    }
    for (const Stretch& stretch : options.movingFrames > 1 ? forestStretches(options.movingFrames)
                                                           : std::vector<Stretch>{}) {
        if (Status measured =
                measureStretch(*renderer.value(), layers, evaluator, stretch, settings, moving);
            !measured) {
            return measured;
        }
    }
    return {};
}

double mean(const std::vector<double>& values) {
    double sum = 0.0;
    for (double value : values) {
        sum += value;
    }
    return values.empty() ? 0.0 : sum / double(values.size());
}

void addMovingMetrics(const MovingSamples& flight, const MovingSamples& forest,
                      std::map<std::string, double>& metrics) {
    if (flight.with.empty() || forest.with.empty()) {
        return;
    }
    const double terrain = median(flight.with) / std::max(median(flight.without), 1e-9);
    const double trees = median(forest.with) / std::max(median(forest.without), 1e-9);
    metrics["shadow_frame_ratio_moving"] = std::max(terrain, trees);
    metrics["shadow_frame_ratio_moving_terrain"] = terrain;
    metrics["shadow_frame_ratio_moving_forest"] = trees;
    // Means show the frames that redraw a cascade, which the medians pass over.
    const double terrainMean = mean(flight.with) / std::max(mean(flight.without), 1e-9);
    const double forestMean = mean(forest.with) / std::max(mean(forest.without), 1e-9);
    metrics["shadow_frame_ratio_moving_mean"] = std::max(terrainMean, forestMean);
    metrics["shadow_frame_ratio_moving_mean_terrain"] = terrainMean;
    metrics["shadow_frame_ratio_moving_mean_forest"] = forestMean;
    metrics["shadow_ms_median_moving_terrain"] = median(flight.shadowPass);
    metrics["shadow_ms_median_moving_forest"] = median(forest.shadowPass);
    metrics["shadow_ms_max_moving_terrain"] =
        *std::max_element(flight.shadowPass.begin(), flight.shadowPass.end());
    metrics["shadow_ms_max_moving_forest"] =
        *std::max_element(forest.shadowPass.begin(), forest.shadowPass.end());
    metrics["shadow_redrawn_cascades_moving_terrain"] =
        double(flight.redrawn) / std::max(flight.cascades, 1);
    metrics["shadow_redrawn_cascades_moving_forest"] =
        double(forest.redrawn) / std::max(forest.cascades, 1);
    metrics["shadow_frames_moving_terrain"] = double(flight.with.size());
    metrics["shadow_frames_moving_forest"] = double(forest.with.size());
}

}  // namespace

Status measureShadows(const ShaderLibrary& library, const ShadingBenchmarkOptions& options,
                      std::map<std::string, double>& metrics) {
    ShadowSamples flight, forest;
    MovingSamples flightMoving, forestMoving;
    if (Status measured = measureFlight(library, options, flight, flightMoving); !measured) {
        return measured;
    }
    if (Status measured = measureForest(library, options, forest, forestMoving); !measured) {
        return measured;
    }
    addMovingMetrics(flightMoving, forestMoving, metrics);
    const double terrainRatio = median(flight.with) / std::max(median(flight.without), 1e-9);
    const double forestRatio = median(forest.with) / std::max(median(forest.without), 1e-9);
    metrics["shadow_frame_ratio"] = std::max(terrainRatio, forestRatio);
    metrics["shadow_frame_ratio_terrain"] = terrainRatio;
    metrics["shadow_frame_ratio_forest"] = forestRatio;
    metrics["shadow_ms_median_terrain"] = median(flight.shadowPass);
    metrics["shadow_ms_median_forest"] = median(forest.shadowPass);
    metrics["shadow_frames_terrain"] = double(flight.with.size());
    metrics["shadow_frames_forest"] = double(forest.with.size());
    metrics["shadow_thresholds_ms"] = forest.thresholdsMs;
    const double terrainOcclusion =
        median(flight.withOcclusion) / std::max(median(flight.with), 1e-9);
    const double forestOcclusion =
        median(forest.withOcclusion) / std::max(median(forest.with), 1e-9);
    metrics["ssao_frame_ratio"] = std::max(terrainOcclusion, forestOcclusion);
    metrics["ssao_frame_ratio_terrain"] = terrainOcclusion;
    metrics["ssao_frame_ratio_forest"] = forestOcclusion;
    metrics["ssao_ms_median_terrain"] = median(flight.occlusionPass);
    metrics["ssao_ms_median_forest"] = median(forest.occlusionPass);
    return {};
}

}  // namespace sylva::bench
