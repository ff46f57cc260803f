#include "ShadowBenchmark.h"
#include "sylva/bench/BenchmarkMetrics.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
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

Status measureFlight(const ShaderLibrary& library, const ShadingBenchmarkOptions& options,
                     ShadowSamples& samples) {
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
    for (const FlightFrame& frame : terrainFlight(grid, options.flightFramesPerSegment)) {
        if (Status measured =
                measureFrame(*renderer.value(), layers, evaluator, frame.camera, settings, samples);
            !measured) {
            return measured;
        }
    }
    return {};
}

Status measureForest(const ShaderLibrary& library, const ShadingBenchmarkOptions& options,
                     ShadowSamples& samples) {
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
    return {};
}

}  // namespace

Status measureShadows(const ShaderLibrary& library, const ShadingBenchmarkOptions& options,
                      std::map<std::string, double>& metrics) {
    ShadowSamples flight, forest;
    if (Status measured = measureFlight(library, options, flight); !measured) {
        return measured;
    }
    if (Status measured = measureForest(library, options, forest); !measured) {
        return measured;
    }
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
