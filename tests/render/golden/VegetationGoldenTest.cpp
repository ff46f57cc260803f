// Golden images of the vegetation renderer (issue 7): one generated oak at four
// distances, rows: the source mesh, the ellipsoid/line LoD, billboard clouds; a forest seen from
// above; and a slow dolly towards a tree whose per-frame image change stays bounded
// (no popping between LoD steps or at the mesh handover).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <numbers>
#include <random>
#include <vector>

#include "GoldenImage.h"
#include "sylva/core/geo/Ellipsoid.h"
#include "sylva/core/plantlod/PlantGenerator.h"
#include "sylva/core/plantlod/PlantLodBuilder.h"
#include "sylva/core/scheduler/TileEvaluator.h"
#include "sylva/core/sources/raster/ConstantSource.h"
#include "sylva/core/sources/raster/NormalMapSource.h"
#include "sylva/render/gl/GlContext.h"
#include "sylva/render/scene/SceneRenderer.h"

namespace sylva::render {
namespace {

constexpr double kDegree = std::numbers::pi / 180;
constexpr double kGround = 50.0;  // metres, the flat test terrain
constexpr double kLatitude = 47.0 * kDegree, kLongitude = 8.0 * kDegree;

class VegetationGolden : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        Result<std::unique_ptr<GlContext>> created = GlContext::create({});
        ASSERT_TRUE(created) << created.error().message;
        context_ = std::move(created.value()).release();
        elevation_ = new ConstantSource("flat", kGround);
        color_ = new ConstantSource("grass", glm::vec4(0.09f, 0.13f, 0.05f, 1.0f));
        normals_ = new NormalMapSource("flat.normals", elevation_, 1.0);
        evaluator_ = new TileEvaluator(TileFormat{256, 2});
        Result<std::unique_ptr<SceneRenderer>> renderer =
            SceneRenderer::create(ShaderLibrary(), TerrainSettings{});
        ASSERT_TRUE(renderer) << renderer.error().message;
        renderer_ = renderer.value().release();

        // A small oak (600 leaves) with a quick LoD build: the same code path as
        // `sylva plant build`, sized for a test.
        Result<TreeParameters> preset = PlantGenerator::preset("oak");
        ASSERT_TRUE(preset);
        PlantGeneratorOptions options;
        options.seed = 3;
        options.leafCount = 600;
        options.leafTextureSize = 64;
        Result<PlantModel> model = PlantGenerator::generate(preset.value(), options);
        ASSERT_TRUE(model) << model.error().message;
        PlantLodOptions lodOptions;
        lodOptions.restarts = 2;
        lodOptions.resolution = 64;
        lodOptions.views = 4;
        lodOptions.ambientOcclusionSamples = 16;
        Result<PlantLod> lod = buildPlantLod(model.value(), lodOptions);
        ASSERT_TRUE(lod) << lod.error().message;
        ASSERT_TRUE(addBillboardClouds(model.value(), lod.value(), lodOptions));
        auto asset = std::make_shared<PlantAsset>();
        asset->name = "oak";
        asset->model = std::move(model.value());
        asset->lod = std::move(lod.value());
        Result<std::uint32_t> species = renderer_->vegetation().addSpecies(asset);
        ASSERT_TRUE(species) << species.error().message;
        species_ = species.value();
    }
    static void TearDownTestSuite() {
        delete renderer_;
        delete evaluator_;
        delete normals_;
        delete color_;
        delete elevation_;
        delete context_;
    }

    // A camera `distance` metres south of the origin, `height` metres above the ground,
    // looking north with `pitch` (radians).
    static Camera camera(double distance, double height, double pitch, double fov) {
        Camera c;
        c.geodetic = {kLatitude - distance / 6367000.0, kLongitude, kGround + height};
        c.position = Ellipsoid::toEcef(c.geodetic);
        c.axes = Camera::axesFromAngles(c.geodetic, 0.0, pitch, 0.0);
        c.verticalFov = fov;
        return c;
    }

    static InstancePlacement placement(double north, double east, float heading, float scale) {
        InstancePlacement p;
        p.latitude = kLatitude + north / 6367000.0;
        p.longitude = kLongitude + east / (6367000.0 * std::cos(kLatitude));
        p.baseEcef = Ellipsoid::toEcef({p.latitude, p.longitude, kGround});
        p.heading = heading;
        p.scale = scale;
        p.species = species_;
        return p;
    }

    static Image render(const Camera& c, int width, int height,
                        const std::vector<const InstanceBatch*>& batches,
                        const VegetationSettings& vegetation, bool sunVisibility = false) {
        RenderSettings settings;
        settings.sunVisibilityOutput = sunVisibility;
        settings.width = width;
        settings.height = height;
        settings.sunDirection =
            glm::normalize(Ellipsoid::surfaceNormal(kLatitude - 0.4, kLongitude - 0.5));
        settings.atmosphere = true;
        settings.ocean = false;
        settings.vegetation = vegetation;
        settings.instanceBatches = batches;
        const TerrainLayers layers{elevation_, color_, normals_, {}, {}};
        Result<Image> image = renderer_->render(layers, *evaluator_, c, settings);
        EXPECT_TRUE(image) << image.error().message;
        return image ? image.value() : Image{};
    }

    static InstanceBatch forest(std::size_t count = 250);

    static GlContext* context_;
    static ConstantSource* elevation_;
    static ConstantSource* color_;
    static NormalMapSource* normals_;
    static TileEvaluator* evaluator_;
    static SceneRenderer* renderer_;
    static std::uint32_t species_;
};
GlContext* VegetationGolden::context_ = nullptr;
ConstantSource* VegetationGolden::elevation_ = nullptr;
ConstantSource* VegetationGolden::color_ = nullptr;
NormalMapSource* VegetationGolden::normals_ = nullptr;
TileEvaluator* VegetationGolden::evaluator_ = nullptr;
SceneRenderer* VegetationGolden::renderer_ = nullptr;
std::uint32_t VegetationGolden::species_ = 0;

// Copies `tile` into `target` at column `x`, row `y` (pixels).
void paste(std::vector<std::uint8_t>& target, int targetWidth, const Image& tile, int x, int y) {
    for (int row = 0; row < tile.height; ++row) {
        std::copy_n(tile.pixels.begin() + std::ptrdiff_t(row) * tile.width * 4, tile.width * 4,
                    target.begin() + (std::ptrdiff_t(y + row) * targetWidth + x) * 4);
    }
}

TEST_F(VegetationGolden, OneTreeAtFourDistancesMeshLodAndBillboards) {
    const InstanceBatch batch =
        LodSelector::makeBatch(placement(0, 0, 0.3f, 1.0f).baseEcef, {placement(0, 0, 0.3f, 1.0f)},
                               renderer_->vegetation().speciesLods());
    constexpr int kTile = 160, kTileHeight = 120;
    const double distances[4] = {30.0, 70.0, 160.0, 420.0};
    std::vector<std::uint8_t> sheet(std::size_t(kTile) * 4 * kTileHeight * 3 * 4, 0);
    const VegetationMethod methods[3] = {VegetationMethod::Mesh, VegetationMethod::Lod,
                                         VegetationMethod::Billboard};
    for (int column = 0; column < 4; ++column) {
        const Camera c = camera(distances[column], 4.0, 6.0 * kDegree, 40.0 * kDegree);
        for (int row = 0; row < 3; ++row) {
            VegetationSettings settings;
            settings.method = methods[row];
            settings.closeUpMesh = false;
            const Image image = render(c, kTile, kTileHeight, {&batch}, settings);
            ASSERT_FALSE(image.pixels.empty());
            paste(sheet, kTile * 4, image, column * kTile, row * kTileHeight);
            const VegetationStatistics& statistics = renderer_->statistics().vegetation;
            EXPECT_EQ(statistics.visibleInstances, 1u) << "distance " << distances[column];
        }
    }
    golden::checkGolden("vegetation_tree_distances", kTile * 4, kTileHeight * 3, sheet);
}

// 250 oaks on 120 m × 120 m, random heading, scale and tint (the first `count`).
InstanceBatch VegetationGolden::forest(std::size_t count) {
    std::mt19937 random(11);
    std::uniform_real_distribution<double> offset(-60.0, 60.0);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::vector<InstancePlacement> placements;
    for (int i = 0; i < 250; ++i) {
        InstancePlacement p = placement(offset(random), offset(random), unit(random) * 6.28f,
                                        0.8f + 0.4f * unit(random));
        p.tint = glm::vec3(0.9f + 0.2f * unit(random));
        placements.push_back(p);
    }
    placements.resize(std::min(count, placements.size()));
    return LodSelector::makeBatch(placement(0, 0, 0, 1).baseEcef, placements,
                                  renderer_->vegetation().speciesLods());
}

TEST_F(VegetationGolden, ForestFromAbove) {
    const InstanceBatch batch = forest();
    const Camera c = camera(110.0, 120.0, -45.0 * kDegree, 50.0 * kDegree);
    const Image image = render(c, 320, 180, {&batch}, VegetationSettings{});
    golden::checkGolden("vegetation_forest_above", 320, 180, image.pixels);
    const VegetationStatistics& statistics = renderer_->statistics().vegetation;
    EXPECT_GT(statistics.visibleInstances, 150u);
    EXPECT_LT(statistics.visibleInstances, 251u);
}

// The forest's shade must not depend on the level of detail the shadow pass draws the
// oaks at (issue 16): the mean sun visibility of the forest view (every pixel; the crowns
// and the ground under them; RenderSettings::sunVisibilityOutput) with the plants'
// shadow error at 3 cascade texels (the default) and at 100 (the coarsest level
// everywhere) against 1 texel (mostly the finest level, the leaves' own ellipsoids). The
// ellipsoid LoD only (no hand-over to the source mesh). Measured: shade (1 − visibility)
// 0.2325 at 3 texels, 0.2457 at 100, 0.2433 at 1, i.e. within 4.4 %; before the shadow
// pass tested the back hits, drew each level with its ShadowThresholds and the level's
// own noise cells, 0.176 and 0.165 (28–32 % less shade). Bar: 7 %; 8 % since
// 2026-12-07: with the image pass's capped noise per tree and its back hits tested
// (ellipsoid.frag) the view shows more of the crowns' inside, 0.1936 / 0.2229 / 0.2079
// (−6.9 %, +7.2 %); the shadow pass is unchanged.
TEST_F(VegetationGolden, ForestShadeDoesNotDependOnTheShadowLevel) {
    const InstanceBatch batch = forest();
    const Camera c = camera(110.0, 120.0, -45.0 * kDegree, 50.0 * kDegree);
    const auto shade = [&](double texels) {
        VegetationSettings vegetation;
        vegetation.shadowErrorTexels = texels;
        vegetation.closeUpMesh = false;
        const Image image = render(c, 320, 180, {&batch}, vegetation, true);
        double visibility = 0.0;
        for (std::size_t i = 1; i < image.pixels.size(); i += 4) {
            visibility += image.pixels[i] / 255.0;
        }
        return 1.0 - visibility / double(image.pixels.size() / 4);
    };
    const double fine = shade(1.0);
    ASSERT_GT(fine, 0.15);  // the view has shade to compare
    for (double texels : {3.0, 100.0}) {
        const double coarse = shade(texels);
        std::printf("shade at %.0f shadow texels %.4f, at 1 texel %.4f\n", texels, coarse, fine);
        EXPECT_NEAR(coarse / fine, 1.0, 0.08) << texels << " texels";
    }
}

// The plants' shadow depth is kept with the terrain's (ShadowMaps' cache, the
// VegetationRenderer's shadowCacheKey) while nothing it depends on changes: a repeated
// view copies every cascade and gives the same image; other batches (a thinned forest)
// draw the split cascades again, and the image follows; equal batches are known by their
// content, not their address.
TEST_F(VegetationGolden, PlantShadowsAreCachedWhileNothingChanges) {
    const InstanceBatch batch = forest();
    const InstanceBatch thinned = forest(125);
    const Camera c = camera(110.0, 120.0, -45.0 * kDegree, 50.0 * kDegree);
    const VegetationSettings vegetation;
    const Image first = render(c, 160, 90, {&batch}, vegetation, true);
    const int cascades = int(renderer_->shadowMaps().cascades().size());
    ASSERT_EQ(cascades, 5);
    EXPECT_EQ(renderer_->vegetation().statistics().shadowCascades, 4u);  // the split ones
    const Image repeated = render(c, 160, 90, {&batch}, vegetation, true);
    EXPECT_EQ(renderer_->shadowMaps().cachedCascades(), cascades);
    EXPECT_EQ(renderer_->vegetation().statistics().shadowCascades, 0u);
    EXPECT_EQ(first.pixels, repeated.pixels);

    const Image thin = render(c, 160, 90, {&thinned}, vegetation, true);
    EXPECT_LE(renderer_->shadowMaps().cachedCascades(), 1);  // at most the terrain-only one
    EXPECT_EQ(renderer_->vegetation().statistics().shadowCascades, 4u);
    EXPECT_NE(thin.pixels, first.pixels);
    const Image thinAgain = render(c, 160, 90, {&thinned}, vegetation, true);
    EXPECT_EQ(renderer_->shadowMaps().cachedCascades(), cascades);
    EXPECT_EQ(renderer_->vegetation().statistics().shadowCascades, 0u);
    EXPECT_EQ(thinAgain.pixels, thin.pixels);
    const Image back = render(c, 160, 90, {&batch}, vegetation, true);
    EXPECT_LE(renderer_->shadowMaps().cachedCascades(), 1);
    EXPECT_EQ(back.pixels, first.pixels);  // drawn again: the same as the first time
    // The same trees in another batch object (the stream re-making a tile): a cache hit.
    const InstanceBatch copy = forest();
    const Image same = render(c, 160, 90, {&copy}, vegetation, true);
    EXPECT_EQ(renderer_->vegetation().statistics().shadowCascades, 0u);
    EXPECT_EQ(same.pixels, first.pixels);
}

// Walking towards the forest (16 steps of 30 cm, 0.2° of turn each) keeps the plants'
// shadow depth: the plants are drawn into a split cascade again only when that cascade's
// Earth-fixed box moved (ShadowSettings::recentreMargin; the VegetationRenderer's key
// holds no camera position), a few cascades in all where the former key (the camera in
// whole cascade texels, 1-5 cm here) redrew the four split cascades at every step. The
// last view, its plant depth drawn from earlier cameras, has the shade of a fresh draw (a
// thinned forest in between) within 2 %, and under 2 % of its pixels' sun visibility
// differ by more than 8 of 255 (noise texels at a threshold; 0.7 % seen).
TEST_F(VegetationGolden, PlantShadowsStayCachedWhileWalking) {
    const InstanceBatch batch = forest();
    const VegetationSettings vegetation;
    const auto cameraAt = [&](int step) {
        Camera c = camera(110.0 - 0.3 * step, 20.0, -20.0 * kDegree, 50.0 * kDegree);
        c.axes = Camera::axesFromAngles(c.geodetic, 0.2 * step * kDegree, -20.0 * kDegree, 0.0);
        return c;
    };
    (void)render(cameraAt(0), 160, 90, {&batch}, vegetation, true);
    std::vector<ShadowCascade> previous = renderer_->shadowMaps().cascades();
    ASSERT_EQ(previous.size(), 5u);
    std::size_t plantDraws = 0, splitMoves = 0;
    const int steps = 16;
    Image last;
    for (int step = 1; step <= steps; ++step) {
        last = render(cameraAt(step), 160, 90, {&batch}, vegetation, true);
        const std::vector<ShadowCascade>& cascades = renderer_->shadowMaps().cascades();
        std::size_t moved = 0;
        for (std::size_t i = 0; i < cascades.size(); ++i) {
            moved += !cascades[i].terrainOnly && cascades[i].boxLight != previous[i].boxLight;
        }
        EXPECT_EQ(renderer_->vegetation().statistics().shadowCascades, moved) << "step " << step;
        plantDraws += renderer_->vegetation().statistics().shadowCascades;
        splitMoves += moved;
        previous = cascades;
    }
    std::printf("forest walk: plants drawn into %zu of %d split cascades, %zu boxes moved\n",
                plantDraws, steps * 4, splitMoves);
    EXPECT_LE(plantDraws, 6u);
    // Afresh: another sun empties the cache (render's sun is fixed, so a thinned forest
    // in between, which draws the split cascades again, then the forest).
    const InstanceBatch thinned = forest(125);
    (void)render(cameraAt(steps), 160, 90, {&thinned}, vegetation, true);
    const Image fresh = render(cameraAt(steps), 160, 90, {&batch}, vegetation, true);
    EXPECT_EQ(renderer_->vegetation().statistics().shadowCascades, 4u);
    // The crowns' noise is point-sampled per shadow texel in camera-relative floats, so a
    // depth drawn from another camera flips a few texels whose sample lies at a noise
    // threshold: compare the shade (mean visibility) and count the pixels that changed.
    double lastSum = 0.0, freshSum = 0.0;
    std::size_t changed = 0;
    const std::size_t pixels = fresh.pixels.size() / 4;
    for (std::size_t i = 0; i < pixels; ++i) {
        lastSum += last.pixels[4 * i + 1];
        freshSum += fresh.pixels[4 * i + 1];
        changed += std::abs(int(last.pixels[4 * i + 1]) - int(fresh.pixels[4 * i + 1])) > 8;
    }
    const double shade = 1.0 - freshSum / (255.0 * double(pixels));
    const double shadeCached = 1.0 - lastSum / (255.0 * double(pixels));
    std::printf("forest walk: shade %.4f cached, %.4f fresh; %zu of %zu pixels changed\n",
                shadeCached, shade, changed, pixels);
    EXPECT_GT(shade, 0.05) << "no shadows to compare";
    EXPECT_NEAR(shadeCached / shade, 1.0, 0.02);
    EXPECT_LT(changed, pixels / 50);
}

// A dolly from 300 m to 8 m: every LoD step and the mesh handover happen on the way.
// Popping is a change of the LoD image from one frame to the next that the source mesh
// does not make along the same path: per pixel (LoD(i+1) − LoD(i)) − (mesh(i+1) − mesh(i)).
// A level switch without the screen-door fade changes a whole crown at once.
TEST_F(VegetationGolden, SlowDollyHasNoPopping) {
    const InstanceBatch batch =
        LodSelector::makeBatch(placement(0, 0, 0.3f, 1.0f).baseEcef, {placement(0, 0, 0.3f, 1.0f)},
                               renderer_->vegetation().speciesLods());
    const glm::vec3 crown = renderer_->vegetation().speciesLods()[0].sphereCenter;
    const auto frameAt = [&](int frame, VegetationMethod method, double band) {
        const int frames = 48;
        const double distance = 300.0 * std::pow(8.0 / 300.0, double(frame) / frames);
        const double pitch = std::atan((crown.z - 2.0) / distance);
        VegetationSettings settings;
        settings.method = method;
        settings.transitionBand = band;
        return render(camera(distance, 2.0, pitch, 40.0 * kDegree), 160, 120, {&batch}, settings);
    };
    // The largest spike: a frame's change above both neighbours' (a smooth growth of the
    // change with the tree's screen size is motion, not popping).
    const auto worstPop = [&](double band) {
        std::vector<double> changes;
        Image lodBefore = frameAt(0, VegetationMethod::Lod, band);
        Image meshBefore = frameAt(0, VegetationMethod::Mesh, band);
        for (int frame = 1; frame <= 48; ++frame) {
            Image lod = frameAt(frame, VegetationMethod::Lod, band);
            Image mesh = frameAt(frame, VegetationMethod::Mesh, band);
            double sum = 0.0;
            for (std::size_t i = 0; i < lod.pixels.size(); i += 4) {
                for (int c = 0; c < 3; ++c) {
                    const double d = (double(lod.pixels[i + c]) - lodBefore.pixels[i + c]) -
                                     (double(mesh.pixels[i + c]) - meshBefore.pixels[i + c]);
                    sum += d * d;
                }
            }
            const double change = std::sqrt(sum / (double(lod.pixels.size()) / 4 * 3));
            if (std::getenv("SYLVA_DOLLY_TRACE") != nullptr) {
                std::printf("frame %d: %.2f\n", frame, change);
            }
            changes.push_back(change);
            lodBefore = std::move(lod);
            meshBefore = std::move(mesh);
        }
        double worst = 0.0;
        for (std::size_t i = 1; i + 1 < changes.size(); ++i) {
            worst = std::max(worst, changes[i] - std::max(changes[i - 1], changes[i + 1]));
        }
        return worst;
    };
    const double faded = worstPop(VegetationSettings{}.transitionBand);
    const double unfaded = worstPop(1e-4);
    std::printf(
        "dolly: largest spike of the unexplained per-frame change: %.2f with fades, %.2f without\n",
        faded, unfaded);
    EXPECT_LT(faded, 1.5);
    EXPECT_GT(unfaded, 2.0 * faded) << "the measure no longer sees level switches";
}

}  // namespace
}  // namespace sylva::render
