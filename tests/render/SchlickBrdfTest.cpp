// Schlick's BRDF in the shading pass (issue 16, seed 001 §7.1) against the analytic
// formula of Schlick 1993 evaluated here in double precision: a synthetic G-buffer
// (uniform albedo, no ambient occlusion term so skylight is off, one view-space normal,
// a surface 100 m away) lit by a sun placed in the normal's mirror direction of the
// view axis (the specular peak, where Schlick differs most from Lambert); atmosphere off,
// exposure 1, so each pixel's radiance is f(l, v) E_sun cos θ with E_sun the sun's
// illuminance after the CPU oracle's transmittance (AtmosphereModel).
#include <gtest/gtest.h>

#include <glad/gl.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <vector>

#include "sylva/core/atmosphere/AtmosphereModel.h"
#include "sylva/core/geo/Ellipsoid.h"
#include "sylva/render/gl/GlContext.h"
#include "sylva/render/gl/ShaderLibrary.h"
#include "sylva/render/scene/SceneRenderer.h"
#include "sylva/render/shading/ShadingPass.h"

namespace sylva::render {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDegree = kPi / 180.0;

glm::dvec3 toSphere(const glm::dvec3& ecef) {
    return {ecef.x, ecef.y, ecef.z * Ellipsoid::kSemiMajorAxis / Ellipsoid::kSemiMinorAxis};
}

// Schlick 1993, isotropic double material: (1 - S) ρ/π + S G(v) G(v') Z(t) / (4π v v').
double schlick(double albedo, double roughness, double f0, const glm::dvec3& n, const glm::dvec3& l,
               const glm::dvec3& v) {
    const double lightCos = glm::dot(n, l), viewCos = glm::dot(n, v);
    if (lightCos <= 0.0) {
        return 0.0;
    }
    const glm::dvec3 h = glm::normalize(l + v);
    const double t = glm::dot(n, h), u = glm::dot(v, h);
    const double fresnel = f0 + (1.0 - f0) * std::pow(1.0 - u, 5.0);
    const double z = roughness / std::pow(1.0 + roughness * t * t - t * t, 2.0);
    auto g = [&](double c) { return c / (roughness - roughness * c + c); };
    return (1.0 - fresnel) * albedo / kPi +
           fresnel * g(viewCos) * g(lightCos) * z / (4.0 * kPi * viewCos * lightCos);
}

struct MaterialCase {
    float code;            // the G-buffer's normal.w
    double roughness, f0;  // as shade.frag's table
};

TEST(SchlickBrdf, ShadingPassMatchesTheAnalyticBrdf) {
    Result<std::unique_ptr<GlContext>> context = GlContext::create({});
    ASSERT_TRUE(context) << context.error().message;
    Result<std::unique_ptr<ShadingPass>> pass = ShadingPass::create(ShaderLibrary());
    ASSERT_TRUE(pass) << pass.error().message;
    const int width = 21, height = 15;
    Camera camera;
    camera.geodetic = Geodetic{47.0 * kDegree, 8.0 * kDegree, 2.0};
    camera.position = Ellipsoid::toEcef(camera.geodetic);
    camera.axes = Camera::axesFromAngles(camera.geodetic, 0.0, 0.0, 0.0);
    camera.verticalFov = 30.0 * kDegree;
    const double near = 0.5, distance = 100.0, albedo = 0.3;
    // Ground seen at a grazing 11°, the sun in the mirror direction of the view axis
    // (22.6° above the horizon ahead): view space, +z towards the viewer.
    const glm::dvec3 normal = glm::normalize(glm::dvec3(0.0, 1.0, 0.2));
    const glm::dvec3 axis(0.0, 0.0, 1.0);
    const glm::dvec3 sunView = 2.0 * glm::dot(normal, axis) * normal - axis;
    const glm::dvec3 sunEcef = glm::normalize(camera.axes * sunView);
    const AtmosphereParameters atmosphere = AtmosphereParameters::fromVisibility(30000.0).value();
    const AtmosphereModel model(atmosphere);
    const glm::dmat4 projection =
        SceneRenderer::projection(camera.verticalFov, double(width) / height, near);
    for (const MaterialCase& material :
         {MaterialCase{0.0f, 0.8, 0.04}, MaterialCase{3.0f, 0.6, 0.04}}) {
        Result<Framebuffer> gbuffer =
            Framebuffer::create(width, height, {GL_RGBA16F, GL_RGBA16F}, true);
        Result<Framebuffer> output =
            Framebuffer::create(width, height, {GL_RGBA8, GL_RGBA32F}, false);
        ASSERT_TRUE(gbuffer && output);
        gbuffer->bind();
        gbuffer->clearColor(0, glm::vec4(float(albedo), float(albedo), float(albedo), 0.0f));
        gbuffer->clearColor(1, glm::vec4(glm::vec3(normal), material.code));
        gbuffer->clearDepth(float(near / distance));
        ShadingSettings settings;
        settings.sunDirection = sunEcef;
        settings.atmosphere = false;
        settings.atmosphereParameters = atmosphere;
        settings.exposure = 1.0;
        pass.value()->run(gbuffer.value(), output.value(), camera, projection, near, settings);
        const std::vector<float> image = output->readPixelsFloat(1, 4);
        Framebuffer::unbind();
        int checked = 0;
        for (int y = 1; y < height; y += 6) {
            for (int x = 1; x < width; x += 9) {
                // The pixel's ray as the shading pass reconstructs it (rows read top first).
                const glm::dvec2 ndc((x + 0.5) / width * 2.0 - 1.0, 1.0 - (y + 0.5) / height * 2.0);
                const glm::dvec3 ray = glm::normalize(
                    glm::dvec3(ndc.x / projection[0][0], ndc.y / projection[1][1], -1.0));
                const glm::dvec3 surface =
                    camera.position + camera.axes * ray * (distance / -ray.z);
                const double sunIlluminance =
                    atmosphere.sunIlluminance *
                    model.transmittanceToTop(toSphere(surface), glm::normalize(toSphere(sunEcef)))
                        .g;
                const double cosine = glm::dot(normal, sunView);
                const double expected =
                    schlick(albedo, material.roughness, material.f0, normal, sunView, -ray) *
                    sunIlluminance * cosine;
                const double lambert = albedo / kPi * sunIlluminance * cosine;
                const double rendered = image[(std::size_t(y) * width + x) * 4 + 1];
                std::printf(
                    "material %g pixel %d,%d: rendered %.1f, Schlick %.1f, Lambert %.1f "
                    "cd/m2\n",
                    material.code, x, y, rendered, expected, lambert);
                EXPECT_NEAR(rendered / expected, 1.0, 0.02)
                    << "material " << material.code << " pixel " << x << "," << y;
                ++checked;
            }
        }
        EXPECT_EQ(checked, 9);
        // At the peak the model is measurably not Lambert (else the test proves nothing).
        const double peak = schlick(albedo, material.roughness, material.f0, normal, sunView, axis);
        EXPECT_GT(peak / (albedo / kPi), 1.1);
    }
}

}  // namespace
}  // namespace sylva::render
