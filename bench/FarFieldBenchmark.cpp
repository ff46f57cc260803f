#include "FarFieldBenchmark.h"
#include "sylva/bench/BenchmarkMetrics.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <vector>

#include "sylva/core/geo/Ellipsoid.h"
#include "sylva/core/scheduler/TileEvaluator.h"
#include "sylva/core/terrain/ElevationQuery.h"
#include "sylva/dsl/ProjectLoader.h"
#include "sylva/render/batch/RenderSetup.h"
#include "sylva/render/scene/SceneRenderer.h"

namespace sylva::bench {
namespace {

constexpr double kDegree = std::numbers::pi / 180;

// The demo's relief, woods and ground camera (projects/demo/demo.sylva), one species.
const char* const kProject = R"sylva(project { title = "Far-field benchmark" }
source height : noise {
    seed = 7
    amplitude = 3km
    base_wavelength = 3000km
    ridges = 60%
    ridge_wavelength = 300km
    roughness = 0.7
    offset = 0m
}
source normals : normal_map { height = @height }
source colour : hypsometric { height = @height; normals = @normals }
source woods : mask {
    input = @height
    expression = "(height > 1700) && (height < 2200)"
    feather = 200m
}
source oak : plant_model { preset = oak; leaves = 1000; seed = 3 }
source forest : plants {
    elevation = @height
    density = @woods
    per_hectare = 80
    spacing = 4m
    species = { oak = 100% }
    models = [@oak]
    seed = 5
}
scenario earth { layers = [@height, @colour, @normals, @forest] }
render { sun = geo(5deg, -40deg); atmosphere = true; ocean = true }
)sylva";

}  // namespace

Result<std::map<std::string, double>> runFarFieldBenchmark(const render::ShaderLibrary& library,
                                                           int width, int height) {
    const std::filesystem::path folder =
        std::filesystem::temp_directory_path() / "sylva_farfield_bench";
    std::error_code error;
    std::filesystem::create_directories(folder, error);
    if (error) {
        return Error{folder.string() + ": " + error.message()};
    }
    std::ofstream(folder / "farfield.sylva") << kProject;
    dsl::LoadResult loaded = dsl::loadProject((folder / "farfield.sylva").string());
    if (loaded.hasErrors()) {
        return Error{loaded.render()};
    }
    const ProjectModel& model = *loaded.model;
    Result<SourceGraph> graph = SourceGraph::build(model);
    if (!graph) {
        return graph.error();
    }
    Result<TerrainLayers> layers = graph.value().terrainLayers(model, "");
    if (!layers) {
        return layers.error();
    }
    Result<render::RenderSetup> setup = render::RenderSetup::fromModel(model, width, height);
    if (!setup) {
        return setup.error();
    }
    Result<std::unique_ptr<render::SceneRenderer>> renderer =
        render::SceneRenderer::create(library, render::TerrainSettings{});
    if (!renderer) {
        return renderer.error();
    }
    TileEvaluator evaluator(TileFormat{256, 2});
    const ElevationQuery query(*layers.value().elevation, evaluator);
    const double latitude = 33.25 * kDegree, longitude = 2.25 * kDegree;
    Result<double> ground = query.groundHeight(latitude, longitude, 20);
    if (!ground) {
        return ground.error();
    }
    std::vector<double> farField, terrain;
    const render::FarFieldFrame* frame = nullptr;
    for (int view = 0; view < 5; ++view) {
        Camera camera;
        camera.geodetic = {latitude, longitude, std::max(ground.value(), 0.0) + 1.7};
        camera.position = Ellipsoid::toEcef(camera.geodetic);
        camera.axes = Camera::axesFromAngles(camera.geodetic, (50.0 + 72.0 * view) * kDegree,
                                             2.0 * kDegree, 0.0);
        camera.verticalFov = 2.0 * std::atan(std::tan(30.0 * kDegree) * height / width);
        for (int pass = 0; pass < 2; ++pass) {  // the first is the warm-up
            Result<render::Image> image =
                renderer.value()->render(layers.value(), evaluator, camera, setup.value().settings);
            if (!image) {
                return image.error();
            }
        }
        const render::RenderStatistics& statistics = renderer.value()->statistics();
        farField.push_back(statistics.farFieldPassSeconds * 1000.0);
        terrain.push_back(statistics.terrainPassSeconds * 1000.0);
        frame = &statistics.farField;
        std::fprintf(stderr, "far field: view %d canopy %.1f ms, terrain %.1f ms\n", view,
                     farField.back(), terrain.back());
    }
    std::map<std::string, double> metrics;
    metrics["farfield_ms_median"] = median(farField);
    metrics["farfield_terrain_ms_median"] = median(terrain);
    metrics["farfield_vs_terrain"] =
        metrics["farfield_ms_median"] / std::max(metrics["farfield_terrain_ms_median"], 1e-6);
    metrics["farfield_levels"] =
        frame->drawn ? frame->levels.finest - frame->levels.coarsest + 1 : 0;
    metrics["farfield_fade_start_m"] = frame->fadeStart;
    metrics["farfield_fade_end_m"] = frame->fadeEnd;
    return metrics;
}

}  // namespace sylva::bench
