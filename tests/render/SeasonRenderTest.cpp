// Seasons and growth drawn by the vegetation renderer (issue 21 item 3), measured on the
// rendered G-buffer:
//  - crown density: one leaf ellipsoid (alpha threshold 0, so at full leaf every pixel
//    of its disc is drawn) keeps the share of its pixels the phenology table gives for
//    the date — January, May and July at 50°N, inverted at 45°S — within 0.06 (the noise
//    has ~800 cells on the disc: 3σ ≈ 0.05);
//  - autumn colour: the drawn albedo is the table's mix of leaf and autumn colour;
//  - close-up mesh: leaf triangles are dropped (leaf-off draws exactly the branches);
//  - growth: a tree planted on 2027-03-01 with a growth curve has, on 2032-03-01 and
//    2042-03-01, the silhouette top of an ellipsoid scaled by the curve (a CPU oracle:
//    the largest elevation angle over the scaled ellipsoid's surface) within 1 % of its
//    height; before planting it is not placed.
#include <gtest/gtest.h>

#include <glad/gl.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "sylva/core/geo/Ellipsoid.h"
#include "sylva/core/plantlod/SyntheticPlant.h"
#include "sylva/core/seasons/Phenology.h"
#include "sylva/core/seasons/PlantSeasons.h"
#include "sylva/core/vegetation/VegetationStream.h"
#include "sylva/render/gl/Framebuffer.h"
#include "sylva/render/gl/GlContext.h"
#include "sylva/render/scene/SceneRenderer.h"
#include "sylva/render/vegetation/VegetationRenderer.h"

namespace sylva::render {
namespace {

constexpr double kDegree = std::numbers::pi / 180;

class SeasonRenderTest : public ::testing::Test {
public:
    static void SetUpTestSuite() {
        Result<std::unique_ptr<GlContext>> created = GlContext::create({});
        ASSERT_TRUE(created) << created.error().message;
        context_ = std::move(created.value()).release();
    }
    static void TearDownTestSuite() {
        delete context_;
        context_ = nullptr;
    }

    // 2 m above the ellipsoid at `latitude`, looking north, level.
    static Camera camera(double latitude, double fov) {
        Camera c;
        c.geodetic = {latitude, 10.0 * kDegree, 2.0};
        c.position = Ellipsoid::toEcef(c.geodetic);
        c.axes = Camera::axesFromAngles(c.geodetic, 0.0, 0.0, 0.0);
        c.verticalFov = fov;
        return c;
    }

    static InstancePlacement placement(const Camera& c, double north) {
        Geodetic g = c.geodetic;
        g.latitude += north / 6367000.0;
        g.height = 0.0;
        InstancePlacement p;
        p.baseEcef = Ellipsoid::toEcef(g);
        p.latitude = g.latitude;
        p.longitude = g.longitude;
        return p;
    }

    // Albedo (RGBA floats, rows top to bottom) of `batch` drawn into a fresh G-buffer.
    static std::vector<float> draw(VegetationRenderer& renderer, const InstanceBatch& batch,
                                   const Camera& c, int width, int height,
                                   const VegetationSettings& settings) {
        Result<Framebuffer> gbuffer =
            Framebuffer::create(width, height, {GL_RGBA16F, GL_RGBA16F}, true);
        EXPECT_TRUE(gbuffer);
        glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
        gbuffer.value().bind();
        gbuffer.value().clearColor(0, glm::vec4(0.0f));
        gbuffer.value().clearColor(1, glm::vec4(0.0f));
        gbuffer.value().clearDepth(0.0f);
        const double near = 0.1;
        const glm::dmat4 projection =
            SceneRenderer::projection(c.verticalFov, double(width) / height, near);
        renderer.draw({&batch}, c, projection, near, width, height, settings);
        std::vector<float> albedo = gbuffer.value().readPixelsFloat(0, 4);
        Framebuffer::unbind();
        glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
        return albedo;
    }

    static std::size_t drawnPixels(const std::vector<float>& albedo) {
        std::size_t count = 0;
        for (std::size_t i = 0; i < albedo.size(); i += 4) {
            count += albedo[i] + albedo[i + 1] + albedo[i + 2] > 0.0f ? 1 : 0;
        }
        return count;
    }

    static GlContext* context_;
};
GlContext* SeasonRenderTest::context_ = nullptr;

const glm::vec3 kLeafColour(0.08f, 0.30f, 0.05f);

std::shared_ptr<PlantAsset> ellipsoidTree(glm::vec3 center, glm::vec3 radii) {
    auto asset = std::make_shared<PlantAsset>();
    asset->name = "crown";
    LodEllipsoid e;
    e.center = center;
    e.radii = radii;
    e.color = kLeafColour;
    e.weight = 1.0f;
    e.noiseLevel = 5.0f;  // 32 noise cells across
    e.alphaThreshold = 0.0f;
    asset->lod.ellipsoids.push_back(e);
    asset->lod.boundsMinimum = center - radii;
    asset->lod.boundsMaximum = center + radii;
    PlantLodLevel level;
    level.ellipsoidCount = 1;
    asset->lod.levels.push_back(level);
    return asset;
}

VegetationSettings lodOnly() {
    VegetationSettings settings;
    settings.closeUpMesh = false;
    settings.minimumPixels = 0.0;
    return settings;
}

PlantDate on(int year, int month, int day) {
    return PlantDate::make(year, month, day).value();
}

// Share of the crown's full-leaf pixels drawn on each date at `latitude`, against the
// table's leaf fraction.
void expectCrownDensity(double latitude, const std::vector<PlantDate>& dates,
                        const std::vector<float>& expectedTable) {
    Result<std::unique_ptr<VegetationRenderer>> renderer =
        VegetationRenderer::create(ShaderLibrary());
    ASSERT_TRUE(renderer) << renderer.error().message;
    ASSERT_TRUE(renderer.value()->addSpecies(ellipsoidTree({0, 0, 4}, {3, 3, 3})));
    const Camera c = SeasonRenderTest::camera(latitude, 40 * kDegree);
    InstancePlacement p = SeasonRenderTest::placement(c, 15.0);
    const InstanceBatch batch =
        LodSelector::makeBatch(p.baseEcef, {p}, renderer.value()->speciesLods());
    renderer.value()->setLeafStates({LeafState{}});
    const std::size_t full = SeasonRenderTest::drawnPixels(
        SeasonRenderTest::draw(*renderer.value(), batch, c, 480, 360, lodOnly()));
    ASSERT_GT(full, 20000u);
    const Phenology table = Phenology::preset(LeafHabit::Deciduous);
    for (std::size_t i = 0; i < dates.size(); ++i) {
        const LeafState state = table.at(dates[i], latitude);
        EXPECT_FLOAT_EQ(state.leafFraction, expectedTable[i]) << dates[i].text();
        renderer.value()->setLeafStates({state});
        const std::size_t drawn = SeasonRenderTest::drawnPixels(
            SeasonRenderTest::draw(*renderer.value(), batch, c, 480, 360, lodOnly()));
        EXPECT_NEAR(double(drawn) / double(full), state.leafFraction, 0.06)
            << dates[i].text() << " at latitude " << latitude / kDegree;
    }
}

TEST_F(SeasonRenderTest, CrownDensityFollowsThePhenologyTable) {
    // 50°N: leaf-off in January, half way through leaf-out on 2 May (day 121.5 of the
    // 104 → 140 ramp is 0.486), full leaf in July.
    const Phenology table = Phenology::preset(LeafHabit::Deciduous);
    const float may = table.onDay(121.0).leafFraction;
    expectCrownDensity(50 * kDegree, {on(2026, 1, 15), on(2026, 5, 2), on(2026, 7, 15)},
                       {0.0f, may, 1.0f});
}

TEST_F(SeasonRenderTest, SouthernHemisphereInvertsTheSeasons) {
    // 45°S: full leaf in January, leaf-off in July; 1 November is the south's 2 May.
    const Phenology table = Phenology::preset(LeafHabit::Deciduous);
    const float november = table.onDay(304.0 + 182.5 - 365.0).leafFraction;
    expectCrownDensity(-45 * kDegree, {on(2026, 1, 15), on(2026, 11, 1), on(2026, 7, 15)},
                       {1.0f, november, 0.0f});
}

TEST_F(SeasonRenderTest, AutumnColourIsTheTablesMix) {
    Result<std::unique_ptr<VegetationRenderer>> renderer =
        VegetationRenderer::create(ShaderLibrary());
    ASSERT_TRUE(renderer) << renderer.error().message;
    ASSERT_TRUE(renderer.value()->addSpecies(ellipsoidTree({0, 0, 4}, {3, 3, 3})));
    const Camera c = camera(50 * kDegree, 40 * kDegree);
    InstancePlacement p = placement(c, 15.0);
    const InstanceBatch batch =
        LodSelector::makeBatch(p.baseEcef, {p}, renderer.value()->speciesLods());
    const LeafState state =
        Phenology::preset(LeafHabit::Deciduous).at(on(2026, 10, 5), 50 * kDegree);
    ASSERT_GT(state.autumn, 0.2f);
    ASSERT_LT(state.autumn, 0.8f);
    renderer.value()->setLeafStates({state});
    const std::vector<float> albedo = draw(*renderer.value(), batch, c, 320, 240, lodOnly());
    // One ellipsoid: its luminance is the species' mean, so the autumn target is the
    // table's colour itself.
    const glm::vec3 expected = glm::mix(kLeafColour, state.autumnColour, state.autumn);
    glm::dvec3 sum(0.0);
    std::size_t count = 0;
    for (std::size_t i = 0; i < albedo.size(); i += 4) {
        if (albedo[i] + albedo[i + 1] + albedo[i + 2] > 0.0f) {
            sum += glm::dvec3(albedo[i], albedo[i + 1], albedo[i + 2]);
            ++count;
        }
    }
    ASSERT_GT(count, 1000u);
    const glm::dvec3 mean = sum / double(count);
    for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(mean[k], expected[k], 0.01 * std::max(expected[k], 0.05f)) << k;
    }
}

TEST_F(SeasonRenderTest, LeafOffDropsTheLeafTrianglesOfTheMesh) {
    Result<std::unique_ptr<VegetationRenderer>> renderer =
        VegetationRenderer::create(ShaderLibrary());
    ASSERT_TRUE(renderer) << renderer.error().message;
    auto withLeaves = std::make_shared<PlantAsset>();
    withLeaves->name = "plant";
    withLeaves->model = makeSyntheticPlant(300, 3);
    glm::vec3 low(1e9f), high(-1e9f);
    for (const PlantMesh& mesh : withLeaves->model.meshes) {
        for (const glm::vec3& v : mesh.positions) {
            low = glm::min(low, v);
            high = glm::max(high, v);
        }
    }
    withLeaves->lod.boundsMinimum = low;
    withLeaves->lod.boundsMaximum = high;
    auto branchesOnly = std::make_shared<PlantAsset>(*withLeaves);
    std::erase_if(branchesOnly->model.meshes,
                  [](const PlantMesh& mesh) { return mesh.part == PlantPart::Leaf; });
    ASSERT_LT(branchesOnly->model.meshes.size(), withLeaves->model.meshes.size());
    ASSERT_TRUE(renderer.value()->addSpecies(withLeaves));
    ASSERT_TRUE(renderer.value()->addSpecies(branchesOnly));
    const double distance = 2.5 * (high.z - low.z);
    const Camera c = camera(50 * kDegree, 50 * kDegree);
    InstancePlacement p = placement(c, distance);
    p.baseEcef -= Ellipsoid::surfaceNormal(c.geodetic.latitude, c.geodetic.longitude) *
                  (0.5 * (high.z - low.z) - 2.0);  // the crown's middle at eye height
    InstancePlacement q = p;
    q.species = 1;
    const InstanceBatch leafy =
        LodSelector::makeBatch(p.baseEcef, {p}, renderer.value()->speciesLods());
    const InstanceBatch bare =
        LodSelector::makeBatch(q.baseEcef, {q}, renderer.value()->speciesLods());
    VegetationSettings mesh;
    mesh.method = VegetationMethod::Mesh;
    mesh.minimumPixels = 0.0;
    LeafState winter;
    winter.leafFraction = 0.0f;
    renderer.value()->setLeafStates({winter, LeafState{}});
    const std::vector<float> leafOff = draw(*renderer.value(), leafy, c, 320, 240, mesh);
    const std::vector<float> branches = draw(*renderer.value(), bare, c, 320, 240, mesh);
    EXPECT_EQ(leafOff, branches);  // exactly the branches
    renderer.value()->setLeafStates({LeafState{}, LeafState{}});
    const std::size_t summer = drawnPixels(draw(*renderer.value(), leafy, c, 320, 240, mesh));
    LeafState spring;
    spring.leafFraction = 0.5f;
    renderer.value()->setLeafStates({spring, LeafState{}});
    const std::size_t half = drawnPixels(draw(*renderer.value(), leafy, c, 320, 240, mesh));
    EXPECT_GT(drawnPixels(branches), 100u);
    EXPECT_LT(drawnPixels(branches), half);
    EXPECT_LT(half, summer);
}

// The apparent top (metres at the tree's distance, above the ground) of an upright
// ellipsoid of horizontal radius a and half-height c centred zc above the ground, seen
// level from eye height e at horizontal distance d: the largest elevation angle over its
// outline in the vertical plane through the eye (the silhouette's top lies in it).
double apparentTop(double a, double c, double zc, double e, double d) {
    double best = -1e9;
    for (int i = 0; i < 200000; ++i) {
        const double phi = 2.0 * std::numbers::pi * i / 200000.0;
        best = std::max(best, std::atan2(zc + c * std::sin(phi) - e, d + a * std::cos(phi)));
    }
    return e + d * std::tan(best);
}

TEST_F(SeasonRenderTest, PlantedTreeHasTheCurvesHeightFifteenYearsOn) {
    Result<std::unique_ptr<VegetationRenderer>> renderer =
        VegetationRenderer::create(ShaderLibrary());
    ASSERT_TRUE(renderer) << renderer.error().message;
    // A 10 m tree: the crown from the ground to 10 m, 3 m wide.
    ASSERT_TRUE(renderer.value()->addSpecies(ellipsoidTree({0, 0, 5}, {1.5f, 1.5f, 5})));
    const double modelHeight = renderer.value()->speciesLods()[0].height;
    ASSERT_FLOAT_EQ(modelHeight, 10.0f);
    // Planted as 1 m whips; 60 % of the model's height with 40 % of its crown at 15.
    std::vector<GrowthCurve::Point> points(3);
    points[0].age = 0;
    points[0].heightMetres = 1.0;
    points[1].age = 15;
    points[1].sizeFraction = 0.6;
    points[1].crownFraction = 0.4;
    points[2].age = 40;
    points[2].sizeFraction = 1.0;
    const PlantSeasons seasons =
        PlantSeasons::planting(on(2027, 3, 1), GrowthCurve::fromPoints(points));
    const Camera c = camera(50 * kDegree, 20 * kDegree);
    const double distance = 25.0;
    InstancePlacement before = placement(c, distance);
    EXPECT_FALSE(VegetationStream::grow(seasons, on(2027, 2, 28), modelHeight, before));
    const int width = 360, height = 720;
    for (const int years : {5, 15}) {
        const PlantDate date = on(2027 + years, 3, 1);
        const double age = date.yearsSince(on(2027, 3, 1));
        const GrowthScale scale = seasons.growth().at(age, modelHeight).value();
        EXPECT_NEAR(scale.height, years == 15 ? 0.6 : 0.1 + 0.5 * 5.0 / 15.0, 1e-3);
        InstancePlacement p = placement(c, distance);
        ASSERT_TRUE(VegetationStream::grow(seasons, date, modelHeight, p));
        const InstanceBatch batch =
            LodSelector::makeBatch(p.baseEcef, {p}, renderer.value()->speciesLods());
        const std::vector<float> albedo =
            draw(*renderer.value(), batch, c, width, height, lodOnly());
        // The topmost drawn row of the middle columns (rows are stored top to bottom).
        int top = -1;
        for (int y = 0; y < height && top < 0; ++y) {
            for (int x = width / 2 - 20; x < width / 2 + 20; ++x) {
                const std::size_t i = (std::size_t(y) * width + x) * 4;
                if (albedo[i] + albedo[i + 1] + albedo[i + 2] > 0.0f) {
                    top = y;
                    break;
                }
            }
        }
        ASSERT_GE(top, 0);
        // The pixel row's upper edge → elevation angle → metres at the tree's distance.
        const double ndc = 1.0 - double(top) / height * 2.0;
        const double measured = 2.0 + distance * ndc * std::tan(c.verticalFov / 2);
        const double treeHeight = 10.0 * scale.height;
        const double expected =
            apparentTop(1.5 * scale.crown, 5.0 * scale.height, 5.0 * scale.height, 2.0, distance);
        EXPECT_NEAR(measured, expected, 0.01 * treeHeight) << years << " years";
        EXPECT_NEAR(expected, treeHeight, 0.01 * treeHeight);  // the silhouette ≈ the top
    }
}

}  // namespace
}  // namespace sylva::render
