// Occlusion culling of plants (issue 21 item 2) on the benchmark's path (SceneRenderer with
// instance batches over terrain): a forest behind a hill is culled (instances counted as
// occluded) and the image is bit-identical to the one without culling; a row of trees in
// front of the hill has nothing culled.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <random>
#include <vector>

#include "sylva/core/base/Hash.h"
#include "sylva/core/geo/Ellipsoid.h"
#include "sylva/core/scheduler/TileEvaluator.h"
#include "sylva/core/sources/raster/ConstantSource.h"
#include "sylva/core/sources/raster/NormalMapSource.h"
#include "sylva/core/sources/raster/RasterSource.h"
#include "sylva/render/gl/GlContext.h"
#include "sylva/render/scene/SceneRenderer.h"

namespace sylva::render {
namespace {

constexpr double kDegree = std::numbers::pi / 180;
constexpr double kLatitude = 46.0 * kDegree, kLongitude = 8.0 * kDegree;
constexpr double kMetresPerRadian = 6367000.0;

// A ridge running east–west 150 m north of the camera: 40 m high, ~30 m wide (Gaussian).
double ridgeHeight(double latitude) {
    const double north = (latitude - kLatitude) * kMetresPerRadian;
    return 40.0 * std::exp(-std::pow((north - 150.0) / 30.0, 2.0));
}

class RidgeElevation final : public Source {
public:
    RidgeElevation() : Source("ridge", "test", PortType::Elevation, 1) {
        setParameterHash(ContentHash().add(std::string_view("ridge-v1")).value());
    }
    Result<TilePointer> produce(const TileKey& key, TileProvider& provider) const override {
        const TileFormat& format = provider.format();
        auto tile = std::make_shared<ImageTile>(key, format.size, format.border, 1);
        for (int iy = -format.border; iy < format.size + format.border; ++iy) {
            for (int ix = -format.border; ix < format.size + format.border; ++ix) {
                tile->at(ix, iy, 0) = float(ridgeHeight(tile->texelLatitude(iy)));
            }
        }
        return TilePointer(tile);
    }
};

// A tree: a crown of 40 random ellipsoids (radius 0.3–0.6 m) in a 2.5 m ball 6 m up, and
// a trunk line; one level, drawn at every error.
std::shared_ptr<PlantAsset> makeTree() {
    auto asset = std::make_shared<PlantAsset>();
    asset->name = "tree";
    std::mt19937 random(3);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    while (asset->lod.ellipsoids.size() < 40) {
        const glm::vec3 p(unit(random), unit(random), unit(random));
        if (glm::length(p) > 1.0f) {
            continue;
        }
        LodEllipsoid e;
        e.center = glm::vec3(0.0f, 0.0f, 6.0f) + 2.5f * p;
        e.radii = glm::vec3(0.6f, 0.45f, 0.3f) * (0.75f + 0.25f * unit(random));
        e.color = glm::vec3(0.1f, 0.3f, 0.05f);
        e.weight = 1.0f;
        asset->lod.ellipsoids.push_back(e);
    }
    LodLine trunk;
    trunk.end = glm::vec3(0.0f, 0.0f, 5.0f);
    trunk.startRadius = 0.25f;
    trunk.endRadius = 0.15f;
    trunk.color = glm::vec3(0.2f, 0.15f, 0.1f);
    asset->lod.lines.push_back(trunk);
    asset->lod.boundsMinimum = glm::vec3(-3.1f, -3.1f, 0.0f);
    asset->lod.boundsMaximum = glm::vec3(3.1f, 3.1f, 9.1f);
    PlantLodLevel level;
    level.ellipsoidCount = 40;
    asset->lod.levels.push_back(level);
    return asset;
}

class VegetationOcclusionTest : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        Result<std::unique_ptr<GlContext>> created = GlContext::create({});
        ASSERT_TRUE(created) << created.error().message;
        context_ = std::move(created.value()).release();
        elevation_ = new RidgeElevation();
        normals_ = new NormalMapSource("ridge.normals", elevation_, 1.0);
        color_ = new ConstantSource("meadow", glm::vec4(0.1f, 0.14f, 0.05f, 1.0f));
        evaluator_ = new TileEvaluator(TileFormat{256, 2});
        Result<std::unique_ptr<SceneRenderer>> renderer =
            SceneRenderer::create(ShaderLibrary(), TerrainSettings{});
        ASSERT_TRUE(renderer) << renderer.error().message;
        renderer_ = renderer.value().release();
        Result<std::uint32_t> species = renderer_->vegetation().addSpecies(makeTree());
        ASSERT_TRUE(species) << species.error().message;
    }
    static void TearDownTestSuite() {
        delete renderer_;
        delete evaluator_;
        delete color_;
        delete normals_;
        delete elevation_;
        delete context_;
    }

    // 2 m above the ground, looking north, 3° up.
    static Camera camera() {
        Camera c;
        c.geodetic = {kLatitude, kLongitude, 2.0};
        c.position = Ellipsoid::toEcef(c.geodetic);
        c.axes = Camera::axesFromAngles(c.geodetic, 0.0, 3.0 * kDegree, 0.0);
        c.verticalFov = 50.0 * kDegree;
        return c;
    }

    // Trees on a jittered `spacing` grid, rows from `north0` to `north1` metres north of the
    // camera, `east` metres either side; standing on the ridge's ground.
    static InstanceBatch forest(double north0, double north1, double east, double spacing) {
        std::mt19937 random(11);
        std::uniform_real_distribution<double> unit(0.0, 1.0);
        std::vector<InstancePlacement> placements;
        for (double n = north0; n <= north1; n += spacing) {
            for (double e = -east; e <= east; e += spacing) {
                InstancePlacement p;
                p.latitude = kLatitude + (n + unit(random)) / kMetresPerRadian;
                p.longitude =
                    kLongitude + (e + unit(random)) / (kMetresPerRadian * std::cos(kLatitude));
                p.baseEcef = Ellipsoid::toEcef({p.latitude, p.longitude, ridgeHeight(p.latitude)});
                p.heading = float(unit(random) * 6.28);
                p.scale = float(0.8 + 0.4 * unit(random));
                placements.push_back(p);
            }
        }
        const glm::dvec3 origin = Ellipsoid::toEcef({kLatitude, kLongitude, 0.0});
        return LodSelector::makeBatch(origin, placements, renderer_->vegetation().speciesLods());
    }

    struct Rendered {
        Image image;
        VegetationStatistics statistics;
    };
    static Rendered render(const std::vector<const InstanceBatch*>& batches, bool culling) {
        RenderSettings settings;
        settings.width = 320;
        settings.height = 180;
        settings.instanceBatches = batches;
        settings.vegetation.closeUpMesh = false;  // the LoD itself (the asset has no mesh)
        settings.vegetation.occlusionCulling = culling;
        settings.vegetation.occluderDistance = 40.0;
        const TerrainLayers layers{elevation_, color_, normals_, {}, {}};
        Result<Image> image = renderer_->render(layers, *evaluator_, camera(), settings);
        EXPECT_TRUE(image) << image.error().message;
        return {image ? image.value() : Image{}, renderer_->statistics().vegetation};
    }

    static std::size_t differingPixels(const Image& a, const Image& b) {
        EXPECT_EQ(a.pixels.size(), b.pixels.size());
        std::size_t differing = 0;
        for (std::size_t i = 0; i + 3 < std::min(a.pixels.size(), b.pixels.size()); i += 4) {
            differing += a.pixels[i] != b.pixels[i] || a.pixels[i + 1] != b.pixels[i + 1] ||
                                 a.pixels[i + 2] != b.pixels[i + 2]
                             ? 1
                             : 0;
        }
        return differing;
    }

    static GlContext* context_;
    static RidgeElevation* elevation_;
    static NormalMapSource* normals_;
    static ConstantSource* color_;
    static TileEvaluator* evaluator_;
    static SceneRenderer* renderer_;
};

GlContext* VegetationOcclusionTest::context_ = nullptr;
RidgeElevation* VegetationOcclusionTest::elevation_ = nullptr;
NormalMapSource* VegetationOcclusionTest::normals_ = nullptr;
ConstantSource* VegetationOcclusionTest::color_ = nullptr;
TileEvaluator* VegetationOcclusionTest::evaluator_ = nullptr;
SceneRenderer* VegetationOcclusionTest::renderer_ = nullptr;

// Trees in front of the ridge (30–90 m) and a forest behind it (220–400 m, hidden by the
// 40 m ridge at 150 m): the hidden forest is culled, and the image does not change.
TEST_F(VegetationOcclusionTest, AForestBehindAHillIsCulledAndTheImageIsIdentical) {
    const InstanceBatch front = forest(30.0, 90.0, 60.0, 12.0);
    const InstanceBatch behind = forest(220.0, 400.0, 150.0, 9.0);
    const Rendered off = render({&front, &behind}, false);
    const Rendered on = render({&front, &behind}, true);
    EXPECT_EQ(off.statistics.occludedInstances, 0u);
    EXPECT_GT(off.statistics.visibleInstances, behind.instances.size() / 2);
    // (Nearly) every tree behind the ridge is hidden; the rest are drawn as before.
    EXPECT_GE(on.statistics.occludedInstances, behind.instances.size() * 9 / 10);
    EXPECT_EQ(on.statistics.visibleInstances + on.statistics.occludedInstances,
              off.statistics.visibleInstances);
    EXPECT_LT(on.statistics.ellipsoids, off.statistics.ellipsoids / 2);
    EXPECT_EQ(differingPixels(on.image, off.image), 0u);
}

// Nothing in front of the plants: a single row of trees standing in front of the ridge
// (nothing between them and the camera) has nothing culled.
TEST_F(VegetationOcclusionTest, NothingIsCulledWhenNothingOccludes) {
    const InstanceBatch row = forest(60.0, 60.0, 60.0, 10.0);
    const Rendered off = render({&row}, false);
    const Rendered on = render({&row}, true);
    EXPECT_GT(on.statistics.visibleInstances, 8u);
    EXPECT_EQ(on.statistics.occludedInstances, 0u);
    EXPECT_EQ(on.statistics.visibleInstances, off.statistics.visibleInstances);
    EXPECT_EQ(differingPixels(on.image, off.image), 0u);
}

}  // namespace
}  // namespace sylva::render
