// Golden image of the proposal's drawing (render/objects) at 320x180: a small village on
// gentle hills (tests/render/golden/village.sylva: houses with gable, hip, pyramid and flat
// roofs, a courtyard block, two turbines of the Olinda model), through the whole path
// from the project file (buildings and objects sources, a scenario's layers) to the shaded
// image. Regenerate with `make goldens`, then look at it.
#include <gtest/gtest.h>

#include <algorithm>

#include "GoldenImage.h"
#include "sylva/core/geo/Ellipsoid.h"
#include "sylva/core/model/BlockReader.h"
#include "sylva/core/scheduler/TileEvaluator.h"
#include "sylva/core/terrain/ElevationQuery.h"
#include "sylva/dsl/ProjectLoader.h"
#include "sylva/render/gl/GlContext.h"
#include "sylva/render/scene/SceneRenderer.h"

namespace sylva::render {
namespace {

constexpr int kWidth = 320;
constexpr int kHeight = 180;

TEST(ObjectsGolden, Village) {
    Result<std::unique_ptr<GlContext>> context = GlContext::create({});
    ASSERT_TRUE(context) << context.error().message;
    dsl::LoadResult loaded =
        dsl::loadProject(std::string(SYLVA_TEST_DATA_DIR) + "/render/golden/village.sylva");
    ASSERT_FALSE(loaded.hasErrors()) << loaded.render();
    const ProjectModel model = std::move(*loaded.model);
    Result<SourceGraph> graph = SourceGraph::build(model);
    ASSERT_TRUE(graph) << graph.error().message;
    Result<TerrainLayers> layers = graph.value().terrainLayers(model, "village");
    ASSERT_TRUE(layers) << layers.error().message;
    ASSERT_EQ(layers.value().meshes.size(), 2u);
    TileEvaluator evaluator(TileFormat{256, 2});
    const ElevationQuery query(*layers.value().elevation, evaluator);
    Result<Camera> camera =
        Camera::fromBlock(*model.findCamera("street"), [&](double latitude, double longitude) {
            return query.groundHeight(latitude, longitude, 20);
        });
    ASSERT_TRUE(camera) << camera.error().message;
    Result<std::unique_ptr<SceneRenderer>> renderer =
        SceneRenderer::create(ShaderLibrary(), TerrainSettings{});
    ASSERT_TRUE(renderer) << renderer.error().message;
    RenderSettings settings;
    settings.width = kWidth;
    settings.height = kHeight;
    settings.sunDirection = Ellipsoid::surfaceNormal(25 * std::numbers::pi / 180, 0.0);
    settings.exposure = 0.45;
    Result<Image> image =
        renderer.value()->render(layers.value(), evaluator, camera.value(), settings);
    ASSERT_TRUE(image) << image.error().message;
    const MeshStatistics& meshes = renderer.value()->statistics().meshes;
    EXPECT_GT(meshes.trianglesDrawn, 100u);
    EXPECT_EQ(meshes.placementsDrawn, 2u);
    golden::checkGolden("objects_village", kWidth, kHeight, image.value().pixels);
}

}  // namespace
}  // namespace sylva::render
