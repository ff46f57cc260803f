// Screen-space ambient occlusion (issue 16 item 3; seed 001 §7.1, the horizon-based SSAO
// of Bavoil and Sainz 2008) against an analytic oracle. Synthetic G-buffers are ray cast
// here on the CPU (view space, reversed-Z depth = near / distance along -z):
// - A box (height H, a wall face at x = w, infinite in y and beyond the face) on flat
//   ground, the ground point P at distance x from the wall seen from 45° above, facing the
//   wall. Within the search sphere of radius R the highest wall point seen from P in
//   azimuth φ (the wall d = x / cos φ away) is z = min(H, sqrt(R² − d²)), at elevation
//   sin h = z / sqrt(d² + z²); the occluded solid angle over the hemisphere's 2π is
//   (1/2π) ∫ sin h dφ over |φ| < acos(x/R) (∫ cos α dα from 0 to h per azimuth; Bavoil and
//   Sainz's horizon integral). x → 0 gives 1/2 for a wall taller than R. The pass ignores
//   occluders less than sin h = 0.1 above the tangent plane; the oracle ignores horizons
//   that low (not quite the same set near x = R: within the tolerance).
// - Open flat ground to the horizon, from a walker's and an aircraft's height: nothing
//   occludes (the sky and the depth jump at the horizon must not darken the far ground).
// - A half-pixel shift of the projection (an anti-aliasing sample) leaves the mean
//   occlusion of the crease scene unchanged.
// - The shading pass multiplies only the sky light by the occlusion, never the sun.
#include <gtest/gtest.h>

#include <glad/gl.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <numbers>
#include <vector>

#include "sylva/core/geo/Ellipsoid.h"
#include "sylva/render/gl/GlContext.h"
#include "sylva/render/gl/ShaderLibrary.h"
#include "sylva/render/scene/SceneRenderer.h"
#include "sylva/render/shading/AmbientOcclusionPass.h"
#include "sylva/render/shading/ShadingPass.h"

namespace sylva::render {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDegree = kPi / 180.0;
constexpr double kNear = 0.1;
constexpr double kSinBias = 0.1;  // as shaders/shading/ambient_occlusion.frag
constexpr int kSize = 512;

struct Surface {
    double distance = 0;  // along -z, metres; 0: sky
    glm::dvec3 normal{0, 0, 1};
    double wallDistance = 0;  // BoxScene: from the hit to the wall's plane, metres
};

// The pixel's view ray (z = -1), as the passes reconstruct it; row 0 at the bottom (GL).
glm::dvec3 pixelRay(const glm::dmat4& projection, double x, double y) {
    const glm::dvec2 ndc(x / kSize * 2.0 - 1.0, y / kSize * 2.0 - 1.0);
    return {(ndc.x + projection[2][0]) / projection[0][0],
            (ndc.y + projection[2][1]) / projection[1][1], -1.0};
}

// Ground (world z = 0) with a box whose face is the plane X = wall (the box fills X >=
// wall, every y, up to boxHeight). The eye at (-distance, 0, distance) looks at the world
// origin P (the image centre) from 45° above, facing the wall, so the face is seen well.
struct BoxScene {
    double wall, boxHeight, distance;

    Surface cast(const glm::dvec3& ray) const {
        const glm::dvec3 eye(-distance, 0.0, distance);
        const glm::dvec3 forward = glm::normalize(-eye);
        const glm::dvec3 right = glm::normalize(glm::cross(forward, glm::dvec3(0, 0, 1)));
        const glm::dvec3 up = glm::cross(right, forward);
        // World direction per unit of view depth (view z = -1 maps to forward).
        const glm::dvec3 direction = ray.x * right + ray.y * up + forward;
        auto toView = [&](const glm::dvec3& n) {
            return glm::dvec3(glm::dot(n, right), glm::dot(n, up), -glm::dot(n, forward));
        };
        double best = std::numeric_limits<double>::infinity();
        glm::dvec3 normal(0.0);
        auto consider = [&](double t, const glm::dvec3& n, bool inside) {
            if (inside && t > 0.0 && t < best) {
                best = t;
                normal = n;
            }
        };
        if (direction.z < 0.0) {
            const double t = -eye.z / direction.z;
            consider(t, {0, 0, 1}, eye.x + t * direction.x < wall);
        }
        if (direction.x > 0.0) {
            const double t = (wall - eye.x) / direction.x;
            const double z = eye.z + t * direction.z;
            consider(t, {-1, 0, 0}, z >= 0.0 && z <= boxHeight);
        }
        if (direction.z < 0.0) {
            const double t = (boxHeight - eye.z) / direction.z;
            consider(t, {0, 0, 1}, eye.x + t * direction.x >= wall);
        }
        if (!std::isfinite(best)) {
            return {};
        }
        return {best, toView(normal), wall - (eye.x + best * direction.x)};
    }
};

// Horizontal ground `height` below a camera pitched down by `pitch`: the ground's normal
// in view space is the world's up rotated by the pitch.
Surface castGround(const glm::dvec3& ray, double height, double pitch) {
    const glm::dvec3 up(0.0, std::cos(pitch), std::sin(pitch));
    const double along = glm::dot(ray, up);  // height gained per unit of -z
    if (along >= 0.0) {
        return {};
    }
    return {height / -along, up};
}

struct GBufferFixture {
    Framebuffer gbuffer;

    template <typename Cast>
    void fill(const glm::dmat4& projection, Cast cast) {
        gbuffer =
            std::move(Framebuffer::create(kSize, kSize, {GL_RGBA16F, GL_RGBA16F}, true).value());
        std::vector<float> normals(std::size_t(kSize) * kSize * 4),
            depth(std::size_t(kSize) * kSize);
        for (int y = 0; y < kSize; ++y) {
            for (int x = 0; x < kSize; ++x) {
                const Surface surface = cast(pixelRay(projection, x + 0.5, y + 0.5));
                const std::size_t i = std::size_t(y) * kSize + x;
                depth[i] = surface.distance > 0.0 ? float(kNear / surface.distance) : 0.0f;
                for (int c = 0; c < 3; ++c) {
                    normals[i * 4 + c] = float(surface.normal[c]);
                }
                normals[i * 4 + 3] = 0.0f;
            }
        }
        glTextureSubImage2D(gbuffer.colorTexture(1), 0, 0, 0, kSize, kSize, GL_RGBA, GL_FLOAT,
                            normals.data());
        glTextureSubImage2D(gbuffer.depthTexture(), 0, 0, 0, kSize, kSize, GL_DEPTH_COMPONENT,
                            GL_FLOAT, depth.data());
    }
};

// Rows bottom to top (GL order).
std::vector<float> readOcclusion(std::uint32_t texture) {
    std::vector<float> values(std::size_t(kSize) * kSize);
    glGetTextureImage(texture, 0, GL_RED, GL_FLOAT, GLsizei(values.size() * sizeof(float)),
                      values.data());
    return values;
}

// The analytic occluded fraction at distance x from the wall (see the file comment),
// by the midpoint rule over φ (20000 intervals: far below the tolerance).
double occludedFraction(double x, double radius, double boxHeight) {
    if (x >= radius) {
        return 0.0;
    }
    const double limit = std::acos(x / radius);
    const int n = 20000;
    double sum = 0.0;
    for (int i = 0; i < n; ++i) {
        const double phi = -limit + (i + 0.5) * 2.0 * limit / n;
        const double d = x / std::cos(phi);
        const double z = std::min(boxHeight, std::sqrt(std::max(radius * radius - d * d, 0.0)));
        const double sine = z / std::sqrt(d * d + z * z);
        sum += sine > kSinBias ? sine : 0.0;
    }
    return sum * (2.0 * limit / n) / (2.0 * kPi);
}

class AmbientOcclusionTest : public ::testing::Test {
protected:
    void SetUp() override {
        Result<std::unique_ptr<GlContext>> created = GlContext::create({});
        ASSERT_TRUE(created) << created.error().message;
        context = std::move(created.value());
        Result<std::unique_ptr<AmbientOcclusionPass>> made =
            AmbientOcclusionPass::create(ShaderLibrary());
        ASSERT_TRUE(made) << made.error().message;
        pass = std::move(made.value());
    }

    std::vector<float> occlusion(const GBufferFixture& fixture, const glm::dmat4& used,
                                 const AmbientOcclusionSettings& settings) {
        Result<std::uint32_t> texture = pass->run(fixture.gbuffer, used, kNear, settings);
        EXPECT_TRUE(texture) << texture.error().message;
        return texture ? readOcclusion(texture.value()) : std::vector<float>{};
    }

    std::unique_ptr<GlContext> context;
    std::unique_ptr<AmbientOcclusionPass> pass;
    const glm::dmat4 projection = SceneRenderer::projection(60.0 * kDegree, 1.0, kNear);
};

// The eye 14 m from P, a 5 m box (taller than the sphere: a wall), search radius 2 m
// (the sphere covers about 60 pixels at P).
constexpr double kEyeDistance = 10.0, kBoxHeight = 5.0, kRadius = 2.0;

TEST_F(AmbientOcclusionTest, GroundBesideABoxMatchesTheHorizonIntegral) {
    AmbientOcclusionSettings settings;
    settings.radius = kRadius;
    double largest = 0.0;
    for (double fraction : {0.05, 0.15, 0.3, 0.5, 0.7, 0.9, 1.3}) {
        const double x = fraction * kRadius;
        GBufferFixture fixture;
        const BoxScene scene{x, kBoxHeight, kEyeDistance};
        fixture.fill(projection, [&](const glm::dvec3& ray) { return scene.cast(ray); });
        const std::vector<float> values = occlusion(fixture, projection, settings);
        ASSERT_FALSE(values.empty());
        // The four pixels round the image centre, each the blur's 4 x 4 box of ground
        // pixels (±2 pixels, about ±9 cm): the oracle is averaged over the same pixels.
        double rendered = 0.0, expected = 0.0;
        for (int y = kSize / 2 - 1; y <= kSize / 2; ++y) {
            for (int px = kSize / 2 - 1; px <= kSize / 2; ++px) {
                rendered += values[std::size_t(y) * kSize + px] / 4.0;
                for (int by = y - 2; by <= y + 1; ++by) {
                    for (int bx = px - 2; bx <= px + 1; ++bx) {
                        const Surface ground = scene.cast(pixelRay(projection, bx + 0.5, by + 0.5));
                        expected +=
                            (1.0 - occludedFraction(ground.wallDistance, kRadius, kBoxHeight)) /
                            64.0;
                    }
                }
            }
        }
        std::printf("x = %.2f m: SSAO %.4f, analytic %.4f\n", x, rendered, expected);
        EXPECT_NEAR(rendered, expected, 0.025) << "x = " << x;
        largest = std::max(largest, 1.0 - expected);
    }
    EXPECT_GT(largest, 0.3);  // the crease is measurably dark (else the test proves nothing)
}

TEST_F(AmbientOcclusionTest, StrengthScalesTheOccludedFraction) {
    GBufferFixture fixture;
    const BoxScene scene{0.3 * kRadius, kBoxHeight, kEyeDistance};
    fixture.fill(projection, [&](const glm::dvec3& ray) { return scene.cast(ray); });
    AmbientOcclusionSettings full, half;
    full.radius = half.radius = kRadius;
    half.strength = 0.5;
    const std::vector<float> a = occlusion(fixture, projection, full);
    const std::vector<float> b = occlusion(fixture, projection, half);
    const std::size_t centre = std::size_t(kSize / 2) * kSize + kSize / 2;
    ASSERT_LT(a[centre], 0.8f);
    EXPECT_NEAR(1.0 - b[centre], 0.5 * (1.0 - a[centre]), 0.003);
}

TEST_F(AmbientOcclusionTest, OpenGroundToTheHorizonIsNotDarkened) {
    const glm::dmat4 wide = SceneRenderer::projection(60.0 * kDegree, 1.0, kNear);
    for (double height : {1.7, 500.0}) {
        GBufferFixture fixture;
        fixture.fill(
            wide, [&](const glm::dvec3& ray) { return castGround(ray, height, 10.0 * kDegree); });
        AmbientOcclusionSettings settings;
        settings.radius = height > 100.0 ? 50.0 : 2.0;
        const std::vector<float> values = occlusion(fixture, wide, settings);
        ASSERT_FALSE(values.empty());
        float darkest = 1.0f;
        for (float v : values) {
            darkest = std::min(darkest, v);
        }
        std::printf("flat ground from %.1f m: darkest SSAO %.4f\n", height, darkest);
        EXPECT_GE(darkest, 0.995f) << "camera " << height << " m above flat ground";
    }
}

TEST_F(AmbientOcclusionTest, SubPixelSampleShiftsKeepTheOcclusion) {
    AmbientOcclusionSettings settings;
    settings.radius = kRadius;
    double means[2] = {0, 0};
    for (int shifted = 0; shifted < 2; ++shifted) {
        glm::dmat4 jittered = projection;
        jittered[2][0] += shifted * 1.0 / kSize;  // half a pixel in NDC (2 / kSize per pixel)
        jittered[2][1] -= shifted * 1.0 / kSize;
        GBufferFixture fixture;
        const BoxScene scene{0.4 * kRadius, kBoxHeight, kEyeDistance};
        fixture.fill(jittered, [&](const glm::dvec3& ray) { return scene.cast(ray); });
        const std::vector<float> values = occlusion(fixture, jittered, settings);
        ASSERT_FALSE(values.empty());
        for (float v : values) {
            means[shifted] += v / values.size();
        }
    }
    std::printf("mean SSAO: %.5f, half a pixel shifted %.5f\n", means[0], means[1]);
    EXPECT_LT(means[0], 0.97);
    EXPECT_NEAR(means[0], means[1], 0.002);
}

// Shading: a surface lit only by the sun (albedo.a 0: no sky light) does not change with
// the occlusion texture; one lit only by the sky (a slope turned away from a low sun)
// scales with it.
TEST_F(AmbientOcclusionTest, ShadingOccludesTheSkyLightOnly) {
    Result<std::unique_ptr<ShadingPass>> shading = ShadingPass::create(ShaderLibrary());
    ASSERT_TRUE(shading) << shading.error().message;
    Camera camera;
    camera.geodetic = Geodetic{47.0 * kDegree, 8.0 * kDegree, 2.0};
    camera.position = Ellipsoid::toEcef(camera.geodetic);
    camera.axes = Camera::axesFromAngles(camera.geodetic, 0.0, -90.0 * kDegree, 0.0);
    camera.verticalFov = 30.0 * kDegree;
    const int size = 8;
    const glm::dmat4 proj = SceneRenderer::projection(camera.verticalFov, 1.0, kNear);
    Result<Framebuffer> occlusionTarget = Framebuffer::create(size, size, {GL_R16F}, false);
    ASSERT_TRUE(occlusionTarget);
    occlusionTarget->clearColor(0, glm::vec4(0.5f));
    const glm::dvec3 up =
        Ellipsoid::surfaceNormal(camera.geodetic.latitude, camera.geodetic.longitude);
    const glm::dvec3 east = glm::normalize(glm::cross(glm::dvec3(0, 0, 1), up));
    struct Case {
        float skyTerm;      // albedo.a
        glm::dvec3 sun;     // ECEF
        glm::dvec3 normal;  // ECEF
        double expected;    // rendered with / without the occlusion texture
    };
    for (const Case& c :
         {Case{0.0f, glm::normalize(up + east), up, 1.0},
          Case{1.0f, glm::normalize(0.2 * up + east), glm::normalize(0.3 * up - east), 0.5}}) {
        const glm::dvec3 normalView = glm::transpose(camera.axes) * c.normal;
        double green[2] = {0, 0};
        for (int withOcclusion = 0; withOcclusion < 2; ++withOcclusion) {
            Result<Framebuffer> gbuffer =
                Framebuffer::create(size, size, {GL_RGBA16F, GL_RGBA16F}, true);
            Result<Framebuffer> output =
                Framebuffer::create(size, size, {GL_RGBA8, GL_RGBA32F}, false);
            ASSERT_TRUE(gbuffer && output);
            gbuffer->clearColor(0, glm::vec4(0.3f, 0.3f, 0.3f, c.skyTerm));
            gbuffer->clearColor(1, glm::vec4(glm::vec3(normalView), 0.0f));
            gbuffer->clearDepth(float(kNear / 2.0));
            ShadingSettings settings;
            settings.sunDirection = c.sun;
            settings.atmosphere = false;
            settings.exposure = 1.0;
            settings.ambientOcclusion = withOcclusion ? occlusionTarget->colorTexture(0) : 0;
            shading.value()->run(gbuffer.value(), output.value(), camera, proj, kNear, settings);
            green[withOcclusion] = output->readPixelsFloat(1, 4)[1];
        }
        Framebuffer::unbind();
        std::printf("sky term %.0f: radiance %.4g without, %.4g with occlusion 0.5\n", c.skyTerm,
                    green[0], green[1]);
        ASSERT_GT(green[0], 0.0);
        EXPECT_NEAR(green[1] / green[0], c.expected, 0.01);
    }
}

}  // namespace
}  // namespace sylva::render
