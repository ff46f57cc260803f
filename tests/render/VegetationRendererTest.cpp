// The vegetation renderer's ray casting against analytic intersections (issue 7): a
// ray-cast ellipsoid's depth per pixel equals the ray/quadric intersection computed here
// in double precision, on both paths (point sprite and quad pass), and an ellipsoid
// never draws where terrain in front of it (a wall in the depth buffer) hides it.
#include <gtest/gtest.h>

#include <glad/gl.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtx/component_wise.hpp>
#include <glm/gtx/matrix_operation.hpp>

#include "sylva/core/geo/Ellipsoid.h"
#include "sylva/render/gl/Framebuffer.h"
#include "sylva/render/gl/GlContext.h"
#include "sylva/render/scene/SceneRenderer.h"
#include "sylva/render/vegetation/VegetationRenderer.h"

namespace sylva::render {
namespace {

constexpr double kDegree = std::numbers::pi / 180;

class VegetationRendererTest : public ::testing::Test {
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

    // A camera 2 m above the ellipsoid surface at (45°N, 10°E), looking north and
    // slightly down.
    static Camera camera() {
        Camera c;
        c.geodetic = {45.0 * kDegree, 10.0 * kDegree, 2.0};
        c.position = Ellipsoid::toEcef(c.geodetic);
        c.axes = Camera::axesFromAngles(c.geodetic, 0.0, -2.0 * kDegree, 0.0);
        c.verticalFov = 40 * kDegree;
        return c;
    }

    // A placement `north` metres north of the camera's foot, `up` metres above the surface.
    static InstancePlacement placement(double north, double up, float heading, float scale) {
        Geodetic g = camera().geodetic;
        g.latitude += north / 6367000.0;
        g.height = up;
        InstancePlacement p;
        p.baseEcef = Ellipsoid::toEcef(g);
        p.latitude = g.latitude;
        p.longitude = g.longitude;
        p.heading = heading;
        p.scale = scale;
        return p;
    }

    struct Frame {
        std::vector<float> depth;
        std::vector<float> normal;  // view normals, xyz + material
        std::vector<float> albedo;
    };

    // Draws into a fresh G-buffer whose depth is cleared to `clearDepth` (reversed-Z:
    // 0 is infinitely far; near / d is a wall of terrain d metres ahead).
    static Frame draw(VegetationRenderer& renderer, const InstanceBatch& batch, const Camera& c,
                      int width, int height, double near, const VegetationSettings& settings,
                      float clearDepth = 0.0f) {
        Result<Framebuffer> gbuffer =
            Framebuffer::create(width, height, {GL_RGBA16F, GL_RGBA16F}, true);
        EXPECT_TRUE(gbuffer);
        glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
        gbuffer.value().bind();
        gbuffer.value().clearColor(0, glm::vec4(0.0f));
        gbuffer.value().clearColor(1, glm::vec4(0.0f));
        gbuffer.value().clearDepth(clearDepth);
        const glm::dmat4 projection =
            SceneRenderer::projection(c.verticalFov, double(width) / height, near);
        renderer.draw({&batch}, c, projection, near, width, height, settings);
        Frame frame;
        frame.depth = gbuffer.value().readDepth();
        frame.normal = gbuffer.value().readPixelsFloat(1, 4);
        frame.albedo = gbuffer.value().readPixelsFloat(0, 4);
        Framebuffer::unbind();
        glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
        return frame;
    }

    // The view-space ray through the centre of pixel (x, y) (rows from the top).
    static glm::dvec3 pixelRay(const Camera& c, int x, int y, int width, int height) {
        const double f = 1.0 / std::tan(c.verticalFov / 2);
        const double aspect = double(width) / height;
        const double ndcX = (x + 0.5) / width * 2 - 1, ndcY = 1 - (y + 0.5) / height * 2;
        return glm::dvec3(ndcX * aspect / f, ndcY / f, -1.0);
    }

    static GlContext* context_;
};
GlContext* VegetationRendererTest::context_ = nullptr;

std::shared_ptr<PlantAsset> singleEllipsoid(glm::vec3 center, glm::vec3 radii, glm::mat3 axes) {
    auto asset = std::make_shared<PlantAsset>();
    asset->name = "ellipsoid";
    LodEllipsoid e;
    e.center = center;
    e.axes[0] = axes[0];
    e.axes[1] = axes[1];
    e.axes[2] = axes[2];
    e.radii = radii;
    e.color = glm::vec3(0.2f, 0.5f, 0.1f);
    e.ambientOcclusion = 0.75f;
    e.weight = 1.0f;
    asset->lod.ellipsoids.push_back(e);
    asset->lod.boundsMinimum = center - glm::vec3(glm::compMax(radii));
    asset->lod.boundsMaximum = center + glm::vec3(glm::compMax(radii));
    PlantLodLevel level;
    level.ellipsoidCount = 1;
    asset->lod.levels.push_back(level);
    return asset;
}

// Renders one ellipsoid `north` metres ahead at width × height and compares every
// pixel's depth with the analytic intersection. 25 m ahead at 480 × 360 the ellipsoid is
// a point sprite (~100 px; the renderer does not even issue the quad pass); 12 m ahead at
// 960 × 720 it spans more pixels than llvmpipe's largest point (255) and the quad pass
// draws it. With `wall`, the depth buffer first holds a wall across the view at the
// depth of the ellipsoid's centre (terrain in front of half of it): every pixel whose
// analytic hit is behind the wall keeps the wall and no colour, every pixel in front
// is drawn with its depth.
void expectAnalyticEllipsoidDepth(int width, int height, double north, bool quadPass,
                                  bool wall = false);

// A plant with more billboard levels than the selector's run keys hold is refused with
// its name and the limit, before anything is uploaded; the renderer stays usable.
TEST_F(VegetationRendererTest, SpeciesBeyondTheBillboardLevelLimitAreRefused) {
    Result<std::unique_ptr<VegetationRenderer>> created =
        VegetationRenderer::create(ShaderLibrary());
    ASSERT_TRUE(created) << created.error().message;
    VegetationRenderer& renderer = *created.value();
    auto asset = singleEllipsoid(glm::vec3(0, 0, 1.5f), glm::vec3(1.0f), glm::mat3(1.0f));
    asset->lod.billboards.levels.resize(kMaxBillboardLevels + 1);
    const Result<std::uint32_t> refused = renderer.addSpecies(asset);
    ASSERT_FALSE(refused);
    EXPECT_EQ(refused.error().message,
              "plant 'ellipsoid': 17 billboard levels, the vegetation renderer draws at most 16 "
              "per species");
    EXPECT_EQ(renderer.speciesCount(), 0u);
    const Result<std::uint32_t> added = renderer.addSpecies(
        singleEllipsoid(glm::vec3(0, 0, 1.5f), glm::vec3(1.0f), glm::mat3(1.0f)));
    ASSERT_TRUE(added) << added.error().message;
    EXPECT_EQ(added.value(), 0u);
}

TEST_F(VegetationRendererTest, RayCastEllipsoidDepthEqualsTheAnalyticIntersection) {
    expectAnalyticEllipsoidDepth(480, 360, 25.0, false);
}

TEST_F(VegetationRendererTest, LargeEllipsoidsAreDrawnByTheQuadPassWithTheSameDepth) {
    expectAnalyticEllipsoidDepth(960, 720, 12.0, true);
}

TEST_F(VegetationRendererTest, EllipsoidsNeverDrawInFrontOfTerrainThatHidesThem) {
    expectAnalyticEllipsoidDepth(480, 360, 25.0, false, true);  // point sprite
    expectAnalyticEllipsoidDepth(960, 720, 12.0, true, true);   // quad pass
}

void expectAnalyticEllipsoidDepth(int width, int height, double north, bool quadPass, bool wall) {
    Result<std::unique_ptr<VegetationRenderer>> created =
        VegetationRenderer::create(ShaderLibrary());
    ASSERT_TRUE(created) << created.error().message;
    VegetationRenderer& renderer = *created.value();
    // An oblate, rotated ellipsoid (2 × 1.2 × 0.15 m) 1.5 m above the base.
    const glm::mat3 axes =
        glm::mat3(glm::rotate(glm::mat4(1.0f), 0.6f, glm::normalize(glm::vec3(1, 2, 3))));
    const Result<std::uint32_t> added = renderer.addSpecies(
        singleEllipsoid(glm::vec3(0, 0, 1.5f), glm::vec3(2.0f, 1.2f, 0.15f), axes));
    ASSERT_TRUE(added) << added.error().message;
    const std::uint32_t species = added.value();
    InstancePlacement p = VegetationRendererTest::placement(north, 0.0, 0.4f, 1.3f);
    p.species = species;
    const InstanceBatch batch = LodSelector::makeBatch(p.baseEcef, {p}, renderer.speciesLods());

    const Camera c = VegetationRendererTest::camera();
    const double near = 0.5;
    VegetationSettings settings;
    settings.closeUpMesh = false;

    // The analytic ellipsoid in view space, double precision.
    const glm::dmat3 view = c.viewRotation();
    const InstanceBatch::Instance& instance = batch.instances[0];
    const glm::dmat3 instanceAxes(glm::dvec3(instance.axes[0]), glm::dvec3(instance.axes[1]),
                                  glm::dvec3(instance.axes[2]));
    const glm::dvec3 center = view * (batch.origin - c.position + glm::dvec3(instance.base) +
                                      instanceAxes * glm::dvec3(0, 0, 1.5));
    const glm::dmat3 shape = view * instanceAxes * glm::dmat3(axes) *
                             glm::dmat3(glm::diagonal3x3(glm::dvec3(2.0, 1.2, 0.15)));
    const glm::dmat3 toLocal = glm::inverse(shape);
    const double wallDistance = wall ? -center.z : 0.0;
    const float wallDepth = wall ? float(near / wallDistance) : 0.0f;
    const VegetationRendererTest::Frame frame =
        VegetationRendererTest::draw(renderer, batch, c, width, height, near, settings, wallDepth);

    int inside = 0, agree = 0, coverageMismatch = 0, hidden = 0, hiddenKept = 0;
    double worst = 0.0;
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const glm::dvec3 d = toLocal * VegetationRendererTest::pixelRay(c, x, y, width, height);
            const glm::dvec3 o = toLocal * (-center);
            const double a = glm::dot(d, d), b = glm::dot(o, d), k = glm::dot(o, o) - 1.0;
            const double h = b * b - a * k;
            const float depth = frame.depth[std::size_t(y) * width + x];
            // Ambient occlusion 0.75 in albedo.a marks a drawn ellipsoid pixel.
            const bool drawn = frame.albedo[(std::size_t(y) * width + x) * 4 + 3] > 0.0f;
            // Squared distance of the ray from the centre in the unit-sphere frame: < 1 hits.
            // Pixels within 3 % of the silhouette are left out (coverage may differ there).
            const double miss = glm::dot(o, o) - b * b / a;
            if (miss > 1.03) {
                coverageMismatch += drawn || depth != wallDepth ? 1 : 0;
                continue;
            }
            if (miss > 0.97) {
                continue;
            }
            const double t = (-b - std::sqrt(h)) / a;
            const double z = t;  // the ray's z component is -1
            if (wall && z > wallDistance * (1.0 - 1e-3)) {
                // Behind the wall (or too close to it to tell): must keep the wall.
                if (z > wallDistance * (1.0 + 1e-3)) {
                    ++hidden;
                    hiddenKept += !drawn && depth == wallDepth ? 1 : 0;
                }
                continue;
            }
            ++inside;
            if (depth <= 0.0f || !drawn) {
                continue;
            }
            const double rendered = near / depth;
            const double error = std::abs(rendered - z) / z;
            worst = std::max(worst, error);
            agree += error < 2e-4 ? 1 : 0;
        }
    }
    EXPECT_GT(inside, wall ? 200 : 500);
    EXPECT_EQ(agree, inside) << "worst relative depth error " << worst;
    if (wall) {
        EXPECT_GT(hidden, 200);
        EXPECT_EQ(hiddenKept, hidden);
    }
    EXPECT_EQ(coverageMismatch, 0);
    EXPECT_EQ(renderer.statistics().visibleInstances, 1u);
    EXPECT_EQ(renderer.statistics().quadPassRuns, quadPass ? 1u : 0u);
}

}  // namespace
}  // namespace sylva::render
