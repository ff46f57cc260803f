// The impostors vegetation method (issue 21; seeds 004 §3.2–3.5 and 000 ch. 7), drawn by
// VegetationRenderer into a G-buffer:
// - a plant seen from one of its capture directions covers the pixels and has the depths
//   of its source mesh drawn by the mesh path (the reference), within the texel size;
// - a tilted flat leaf's rendered depth is the analytic ray/plane distance within the
//   impostor's depth resolution (texel footprint × slope);
// - a far tile becomes one group impostor that matches the single impostors it stands
//   for, is kept for a camera move inside its guaranteed valid volume and rendered again
//   (counted) after a move far outside the validity bound (the bound itself is tested
//   against its analytic value in ImpostorValidityTest).
#include <gtest/gtest.h>

#include <glad/gl.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <vector>

#include "sylva/core/geo/Ellipsoid.h"
#include "sylva/core/plantlod/ImpostorViewSet.h"
#include "sylva/render/gl/Framebuffer.h"
#include "sylva/render/gl/GlContext.h"
#include "sylva/render/scene/SceneRenderer.h"
#include "sylva/render/vegetation/VegetationRenderer.h"

namespace sylva::render {
namespace {

constexpr double kDegree = std::numbers::pi / 180;
constexpr int kWidth = 320, kHeight = 180;
constexpr double kNear = 0.5;

class ImpostorRendererTest : public ::testing::Test {
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

    // A camera `height` metres above the ellipsoid at (45°N, 10°E), looking north, level,
    // `east` metres east of the meridian.
    static Camera camera(double height = 2.0, double east = 0.0) {
        Camera c;
        c.geodetic = {45.0 * kDegree, 10.0 * kDegree + east / (6367000.0 * std::cos(45 * kDegree)),
                      height};
        c.position = Ellipsoid::toEcef(c.geodetic);
        c.axes = Camera::axesFromAngles(c.geodetic, 0.0, 0.0, 0.0);
        c.verticalFov = 40 * kDegree;
        return c;
    }

    // A placement `north` and `east` metres from the camera's foot, on the ellipsoid,
    // heading 0 (model +Y north, +X east).
    static InstancePlacement placement(double north, double east = 0.0) {
        Geodetic g = camera().geodetic;
        g.latitude += north / 6367000.0;
        g.longitude += east / (6367000.0 * std::cos(g.latitude));
        g.height = 0.0;
        InstancePlacement p;
        p.baseEcef = Ellipsoid::toEcef(g);
        p.latitude = g.latitude;
        p.longitude = g.longitude;
        return p;
    }

    struct Frame {
        std::vector<float> depth;   // reversed-Z: near / distance
        std::vector<float> albedo;  // rgba; a > 0 where a plant was drawn
        bool covered(std::size_t i) const { return albedo[i * 4 + 3] > 0.0f; }
        double distance(std::size_t i) const { return kNear / double(depth[i]); }
    };

    static Frame draw(VegetationRenderer& renderer,
                      const std::vector<const InstanceBatch*>& batches, const Camera& c,
                      VegetationMethod method) {
        Result<Framebuffer> gbuffer =
            Framebuffer::create(kWidth, kHeight, {GL_RGBA16F, GL_RGBA16F}, true);
        EXPECT_TRUE(gbuffer);
        glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
        gbuffer.value().bind();
        gbuffer.value().clearColor(0, glm::vec4(0.0f));
        gbuffer.value().clearColor(1, glm::vec4(0.0f));
        gbuffer.value().clearDepth(0.0f);
        const glm::dmat4 projection =
            SceneRenderer::projection(c.verticalFov, double(kWidth) / kHeight, kNear);
        VegetationSettings settings;
        settings.method = method;
        settings.closeUpMesh = false;
        settings.minimumPixels = 0.0;
        renderer.draw(batches, c, projection, kNear, kWidth, kHeight, settings);
        Frame frame;
        frame.depth = gbuffer.value().readDepth();
        frame.albedo = gbuffer.value().readPixelsFloat(0, 4);
        Framebuffer::unbind();
        glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
        return frame;
    }

    // The view-space ray through the centre of pixel (x, y) (rows from the top), z = -1.
    static glm::dvec3 pixelRay(const Camera& c, int x, int y) {
        const double f = 1.0 / std::tan(c.verticalFov / 2);
        const double aspect = double(kWidth) / kHeight;
        const double ndcX = (x + 0.5) / kWidth * 2 - 1, ndcY = 1 - (y + 0.5) / kHeight * 2;
        return glm::dvec3(ndcX * aspect / f, ndcY / f, -1.0);
    }

    static GlContext* context_;
};
GlContext* ImpostorRendererTest::context_ = nullptr;

// One double-sided quad (two triangles) with corners a, b, c, d.
void addQuad(PlantMesh& mesh, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d) {
    const std::uint32_t first = std::uint32_t(mesh.positions.size());
    const glm::vec3 normal = glm::normalize(glm::cross(b - a, d - a));
    for (const glm::vec3& p : {a, b, c, d}) {
        mesh.positions.push_back(p);
        mesh.normals.push_back(normal);
        mesh.uvs.emplace_back(0.0f);
    }
    for (std::uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) {
        mesh.indices.push_back(first + i);
    }
}

// A plant of quads inside the box [-2, 2] × [-2, 2] × [0, 4] (sphere centre (0, 0, 2)).
std::shared_ptr<PlantAsset> plantOf(const std::vector<std::array<glm::vec3, 4>>& quads) {
    auto asset = std::make_shared<PlantAsset>();
    asset->name = "quads";
    PlantMesh mesh;
    mesh.part = PlantPart::Leaf;
    for (const auto& q : quads) {
        addQuad(mesh, q[0], q[1], q[2], q[3]);
    }
    asset->model.meshes.push_back(mesh);
    asset->lod.boundsMinimum = glm::vec3(-2.0f, -2.0f, 0.0f);
    asset->lod.boundsMaximum = glm::vec3(2.0f, 2.0f, 4.0f);
    return asset;
}

// Three leaves at different depths along the view axis (model Y), partly overlapping.
std::shared_ptr<PlantAsset> threeLeaves() {
    return plantOf({{glm::vec3(-1.5f, -1.0f, 0.5f), glm::vec3(0.5f, -0.6f, 0.5f),
                     glm::vec3(0.5f, -0.6f, 2.5f), glm::vec3(-1.5f, -1.0f, 2.5f)},
                    {glm::vec3(-0.5f, 0.5f, 1.5f), glm::vec3(1.5f, 1.2f, 1.5f),
                     glm::vec3(1.5f, 1.2f, 3.5f), glm::vec3(-0.5f, 0.5f, 3.5f)},
                    {glm::vec3(-1.8f, 1.5f, 2.8f), glm::vec3(0.0f, 1.8f, 2.8f),
                     glm::vec3(0.0f, 1.0f, 3.8f), glm::vec3(-1.8f, 0.7f, 3.8f)}});
}

std::unique_ptr<VegetationRenderer> makeRenderer() {
    Result<std::unique_ptr<VegetationRenderer>> created =
        VegetationRenderer::create(ShaderLibrary());
    EXPECT_TRUE(created) << created.error().message;
    return created ? std::move(created.value()) : nullptr;
}

// The texel size (metres) of the resolution the renderer picks for the 4 m-wide test
// plant (sphere radius 2√3 m) `distance` metres away.
double texelSize(const Camera& c, double distance) {
    const double radius = 2.0 * std::sqrt(3.0);
    const double pixelAngle = 2.0 * std::tan(c.verticalFov / 2) / kHeight;
    const int level = ImpostorViewSet::resolutionLevel(2.0 * radius / (distance * pixelAngle));
    return 2.0 * radius / ImpostorViewSet::kResolutions[std::size_t(level)];
}

// The camera (2 m up, south of the plant, whose sphere centre is 2 m up) looks at the
// plant along model −Y: the capture view at azimuth 270°, exactly.
TEST_F(ImpostorRendererTest, ImpostorFromItsCaptureDirectionMatchesTheMesh) {
    std::unique_ptr<VegetationRenderer> renderer = makeRenderer();
    ASSERT_TRUE(renderer);
    const Result<std::uint32_t> species = renderer->addSpecies(threeLeaves());
    ASSERT_TRUE(species) << species.error().message;
    const double distance = 30.0;
    const InstanceBatch batch = LodSelector::makeBatch(
        placement(distance).baseEcef, {placement(distance)}, renderer->speciesLods());
    const Camera c = camera();
    const Frame mesh = draw(*renderer, {&batch}, c, VegetationMethod::Mesh);
    const Frame impostor = draw(*renderer, {&batch}, c, VegetationMethod::Impostors);
    EXPECT_EQ(renderer->impostorStatistics().impostorInstances, 1u);
    int both = 0, either = 0, depthAgree = 0;
    const double texel = texelSize(c, distance);
    for (std::size_t i = 0; i < mesh.depth.size(); ++i) {
        const bool a = mesh.covered(i), b = impostor.covered(i);
        either += a || b ? 1 : 0;
        if (a && b) {
            ++both;
            // Leaves are ≤ 1 m deep per metre across (slope ≤ 1): a texel of offset.
            depthAgree += std::abs(mesh.distance(i) - impostor.distance(i)) <= 2.0 * texel ? 1 : 0;
        }
    }
    ASSERT_GT(either, 300);
    EXPECT_GT(double(both) / either, 0.9) << both << " of " << either;
    EXPECT_GT(double(depthAgree) / both, 0.95) << depthAgree << " of " << both;
}

// One leaf, 3 × 3 m, tilted 35° about model X (facing the camera, leaning back): every
// pixel well inside it is drawn at the analytic ray/plane distance within the depth
// resolution of the impostor (0.75 texel of footprint × the slope, plus 1 cm).
TEST_F(ImpostorRendererTest, RenderedDepthIsTheLeafDepth) {
    const float tilt = float(35.0 * kDegree);
    const float s = 1.5f * std::cos(tilt), t = 1.5f * std::sin(tilt);
    std::unique_ptr<VegetationRenderer> renderer = makeRenderer();
    ASSERT_TRUE(renderer);
    // Corners at y = -t (bottom, toward the camera) and +t (top, away), z = 2 ∓ s.
    const Result<std::uint32_t> species = renderer->addSpecies(
        plantOf({{glm::vec3(-1.5f, -t, 2.0f - s), glm::vec3(1.5f, -t, 2.0f - s),
                  glm::vec3(1.5f, t, 2.0f + s), glm::vec3(-1.5f, t, 2.0f + s)}}));
    ASSERT_TRUE(species) << species.error().message;
    const double distance = 25.0;
    const InstancePlacement p = placement(distance);
    const InstanceBatch batch = LodSelector::makeBatch(p.baseEcef, {p}, renderer->speciesLods());
    const Camera c = camera();
    const Frame frame = draw(*renderer, {&batch}, c, VegetationMethod::Impostors);

    // The leaf plane in view space: a point and the normal, from the instance's axes.
    const InstanceBatch::Instance& instance = batch.instances[0];
    const glm::dmat3 view = c.viewRotation();
    const glm::dmat3 axes(glm::dvec3(instance.axes[0]), glm::dvec3(instance.axes[1]),
                          glm::dvec3(instance.axes[2]));
    const glm::dvec3 origin = view * (batch.origin + glm::dvec3(instance.base) - c.position);
    const auto toView = [&](glm::dvec3 model) { return view * (axes * model) + origin; };
    const glm::dvec3 a = toView({-1.5, -t, 2.0 - s}), b = toView({1.5, -t, 2.0 - s});
    const glm::dvec3 d = toView({-1.5, t, 2.0 + s});
    const glm::dvec3 normal = glm::normalize(glm::cross(b - a, d - a));
    const double tolerance = 0.75 * texelSize(c, distance) * std::tan(tilt) + 0.01;
    int inside = 0, drawn = 0, agree = 0;
    double worst = 0.0;
    for (int y = 0; y < kHeight; ++y) {
        for (int x = 0; x < kWidth; ++x) {
            const glm::dvec3 ray = pixelRay(c, x, y);
            const double along = glm::dot(a, normal) / glm::dot(ray, normal);
            const glm::dvec3 hit = ray * along;
            // Leaf coordinates in [0, 1]² (u along a→b, v along a→d), 10 % margin.
            const double u = glm::dot(hit - a, b - a) / glm::dot(b - a, b - a);
            const double v = glm::dot(hit - a, d - a) / glm::dot(d - a, d - a);
            if (u < 0.1 || u > 0.9 || v < 0.1 || v > 0.9) {
                continue;
            }
            ++inside;
            const std::size_t i = std::size_t(y) * kWidth + x;
            if (!frame.covered(i)) {
                continue;
            }
            ++drawn;
            const double error = std::abs(frame.distance(i) - along);  // the ray's z is -1
            worst = std::max(worst, error);
            agree += error <= tolerance ? 1 : 0;
        }
    }
    ASSERT_GT(inside, 200);
    EXPECT_EQ(drawn, inside);
    EXPECT_EQ(agree, drawn) << "worst " << worst << " m, tolerance " << tolerance << " m";
}

// A tile of 25 plants (scaled 3×, 12 m wide) 600–700 m away (each ~9 px): one group impostor; it
// looks like the single impostors, is kept when the camera moves 1 cm (inside its guaranteed valid
// volume) and rendered again after 300 m sideways (parallax ≈ 3 pixels > 1).
TEST_F(ImpostorRendererTest, FarTileIsAGroupImpostorKeptWhileValid) {
    std::unique_ptr<VegetationRenderer> renderer = makeRenderer();
    ASSERT_TRUE(renderer);
    const Result<std::uint32_t> species = renderer->addSpecies(threeLeaves());
    ASSERT_TRUE(species) << species.error().message;
    std::vector<InstancePlacement> placements;
    for (int i = 0; i < 25; ++i) {
        placements.push_back(placement(600.0 + 25.0 * (i / 5), -50.0 + 25.0 * (i % 5)));
        placements.back().scale = 3.0f;
    }
    const InstanceBatch batch =
        LodSelector::makeBatch(placements[12].baseEcef, placements, renderer->speciesLods());
    const Camera c = camera(6.0);

    ImpostorSettings single;
    single.groupPixels = 0.0;
    renderer->setImpostorSettings(single);
    const Frame singles = draw(*renderer, {&batch}, c, VegetationMethod::Impostors);
    EXPECT_EQ(renderer->impostorStatistics().impostorInstances, 25u);
    EXPECT_EQ(renderer->impostorStatistics().groups, 0u);

    renderer->setImpostorSettings(ImpostorSettings{});
    const Frame grouped = draw(*renderer, {&batch}, c, VegetationMethod::Impostors);
    const ImpostorStatistics first = renderer->impostorStatistics();
    EXPECT_EQ(first.impostorInstances, 0u);
    EXPECT_EQ(first.groups, 1u);
    EXPECT_EQ(first.groupInstances, 25u);
    EXPECT_EQ(first.groupsRendered, 1u);
    // Depth: the same leaf within 0.5 m; where rows of trees overlap on screen the
    // resampled group may show the neighbouring row (25 m apart), never anything farther.
    int both = 0, either = 0, depthAgree = 0, beyondRow = 0;
    for (std::size_t i = 0; i < singles.depth.size(); ++i) {
        const bool a = singles.covered(i), b = grouped.covered(i);
        either += a || b ? 1 : 0;
        if (a && b) {
            ++both;
            const double difference = std::abs(singles.distance(i) - grouped.distance(i));
            depthAgree += difference < 0.5 ? 1 : 0;
            beyondRow += difference > 26.0 ? 1 : 0;
        }
    }
    ASSERT_GT(either, 80);
    EXPECT_GT(double(both) / either, 0.85) << both << " of " << either;
    EXPECT_GT(double(depthAgree) / both, 0.85) << depthAgree << " of " << both;
    EXPECT_EQ(beyondRow, 0);

    (void)draw(*renderer, {&batch}, camera(6.0, 0.01), VegetationMethod::Impostors);
    const ImpostorStatistics kept = renderer->impostorStatistics();
    EXPECT_EQ(kept.groupsRendered, 0u);
    EXPECT_EQ(kept.validity.tests, 1u);
    EXPECT_EQ(kept.validity.insideGuaranteedVolume, 1u);

    (void)draw(*renderer, {&batch}, camera(6.0, 300.0), VegetationMethod::Impostors);
    const ImpostorStatistics moved = renderer->impostorStatistics();
    EXPECT_EQ(moved.groupsRendered, 1u);
    EXPECT_EQ(moved.validity.regenerated, 1u);
}

}  // namespace
}  // namespace sylva::render
