// Golden images of the proposal's drawing (render/objects) at 320x180: a small village on
// gentle hills (tests/render/golden/village.sylva: houses with gable, hip, pyramid and flat
// roofs, a courtyard block, two turbines of the Olinda model), and the Olinda project's
// `proposed` scenario (five turbines, the block of houses; needs scripts/fetch-samples),
// through the whole path from the project file (buildings and objects sources, a
// scenario's layers) to the shaded image. Regenerate with `make goldens`, then look at it.
// The Olinda golden also checks what a tolerant image comparison could miss: the
// proposal's own pixels (depth against `today`) and the shadows it casts.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <numbers>

#include "GoldenImage.h"
#include "sylva/core/geo/Ellipsoid.h"
#include "sylva/core/image/ProposalMask.h"
#include "sylva/core/model/BlockReader.h"
#include "sylva/core/scheduler/TileEvaluator.h"
#include "sylva/core/terrain/ElevationQuery.h"
#include "sylva/dsl/ProjectLoader.h"
#include "sylva/render/batch/RenderSetup.h"
#include "sylva/render/gl/GlContext.h"
#include "sylva/render/scene/SceneRenderer.h"

namespace sylva::render {
namespace {

constexpr int kWidth = 320;
constexpr int kHeight = 180;
// The Olinda proposal's camera: latitude, longitude (degrees), metres above the ground,
// heading, pitch (degrees); and the least pixel counts of the proposal and its shadows.
constexpr double kOlindaCamera[5] = {-7.9655, -34.9031, 100.0, 50.0, -20.0};
constexpr int kOlindaProposalPixels = 600;  // 1,539 when made (2026-12-03)
constexpr int kOlindaShadowPixels = 15;     // 36 when made

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

// The Olinda proposal from a drone 170 m south-west of the houses, 100 m above the ground,
// looking north-east down at the houses and on to the turbines, with the project's render block
// (sun from geo(10°, −85°): west-north-west, shadows towards the camera's right). Besides the
// golden image: the proposal covers pixels that `today` shows as terrain or plants (houses
// and turbines: ProposalMask from the two depth buffers), every turbine is drawn, and the
// proposal casts shadows: pixels outside the proposal that the shadows darken in `proposed`
// (with / without shadows < 0.75) but not in `today` (> 0.9).
TEST(ObjectsGolden, OlindaProposal) {
    const std::filesystem::path dem =
        std::filesystem::path(SYLVA_PROJECTS_DIR) / "../data/olinda/olinda_dem_utm25s.tif";
    if (!std::filesystem::exists(dem)) {
        GTEST_SKIP() << "sample data absent (" << dem << "); run scripts/fetch-samples";
    }
    Result<std::unique_ptr<GlContext>> context = GlContext::create({});
    ASSERT_TRUE(context) << context.error().message;
    dsl::LoadResult loaded =
        dsl::loadProject(std::string(SYLVA_PROJECTS_DIR) + "/olinda/olinda.sylva");
    ASSERT_FALSE(loaded.hasErrors()) << loaded.render();
    const ProjectModel model = std::move(*loaded.model);
    Result<SourceGraph> graph = SourceGraph::build(model);
    ASSERT_TRUE(graph) << graph.error().message;
    Result<TerrainLayers> today = graph.value().terrainLayers(model, "today");
    Result<TerrainLayers> proposed = graph.value().terrainLayers(model, "proposed");
    ASSERT_TRUE(today) << today.error().message;
    ASSERT_TRUE(proposed) << proposed.error().message;
    ASSERT_EQ(proposed.value().meshes.size(), 2u);
    TileEvaluator evaluator(TileFormat{256, 2});
    const ElevationQuery query(*proposed.value().elevation, evaluator);
    constexpr double kDegree = std::numbers::pi / 180.0;
    Camera camera;
    const double latitude = kOlindaCamera[0] * kDegree, longitude = kOlindaCamera[1] * kDegree;
    Result<double> ground = query.groundHeight(latitude, longitude, 16);
    ASSERT_TRUE(ground) << ground.error().message;
    camera.geodetic = {latitude, longitude, ground.value() + kOlindaCamera[2]};
    camera.position = Ellipsoid::toEcef(camera.geodetic);
    camera.axes = Camera::axesFromAngles(camera.geodetic, kOlindaCamera[3] * kDegree,
                                         kOlindaCamera[4] * kDegree, 0.0);
    camera.verticalFov = 50 * kDegree;
    Result<std::unique_ptr<SceneRenderer>> renderer =
        SceneRenderer::create(ShaderLibrary(), TerrainSettings{});
    ASSERT_TRUE(renderer) << renderer.error().message;
    Result<RenderSetup> setup = RenderSetup::fromModel(model, kWidth, kHeight);
    ASSERT_TRUE(setup) << setup.error().message;
    struct Frame {
        std::vector<std::uint8_t> pixels;
        std::vector<float> depth;
    };
    const auto render = [&](const TerrainLayers& layers, bool shadows) {
        RenderSettings settings = setup.value().settings;
        settings.shadows.enabled = shadows;
        Result<Image> image = renderer.value()->render(layers, evaluator, camera, settings);
        EXPECT_TRUE(image) << image.error().message;
        return Frame{image ? image.value().pixels : std::vector<std::uint8_t>{},
                     renderer.value()->depth()};
    };
    const Frame withProposal = render(proposed.value(), true);
    const MeshStatistics meshes = renderer.value()->statistics().meshes;
    const Frame withoutShadows = render(proposed.value(), false);
    const Frame before = render(today.value(), true);
    const Frame beforeUnshadowed = render(today.value(), false);
    ASSERT_EQ(withProposal.pixels.size(), std::size_t(kWidth) * kHeight * 4);
    EXPECT_EQ(meshes.placementsDrawn, 5u) << "every turbine";
    EXPECT_GT(meshes.trianglesDrawn, 300u);
    const PixelMask mask =
        ProposalMask::fromDepths(before.depth, withProposal.depth, kWidth, kHeight);
    const auto luminance = [](const Frame& frame, std::size_t i) {
        return 0.2126 * frame.pixels[4 * i] + 0.7152 * frame.pixels[4 * i + 1] +
               0.0722 * frame.pixels[4 * i + 2] + 1.0;
    };
    int proposal = 0, castShadow = 0;
    for (std::size_t i = 0; i < mask.size(); ++i) {
        proposal += mask[i];
        if (mask[i] == 0 && withProposal.depth[i] > 0.0f &&
            luminance(withProposal, i) < 0.75 * luminance(withoutShadows, i) &&
            luminance(before, i) > 0.9 * luminance(beforeUnshadowed, i)) {
            ++castShadow;
        }
    }
    std::printf("olinda proposal: %d proposal pixels, %d pixels shadowed by it\n", proposal,
                castShadow);
    EXPECT_GT(proposal, kOlindaProposalPixels) << "the houses and turbines must show";
    EXPECT_GT(castShadow, kOlindaShadowPixels) << "the proposal must cast shadows";
    golden::checkGolden("objects_olinda_proposal", kWidth, kHeight, withProposal.pixels);
}

}  // namespace
}  // namespace sylva::render
