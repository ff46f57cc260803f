#include "sylva/render/shading/ShadingPass.h"

#include <glad/gl.h>

#include "AtmosphereLuts.h"
#include "sylva/core/geo/Ellipsoid.h"

namespace sylva::render {
namespace {

// Texture units: 0-2 the G-buffer, 3-8 the atmosphere's tables (AtmosphereLuts::bind),
// the screen-space ambient occlusion, then the shadow maps.
constexpr int kAmbientOcclusionUnit = 9;
constexpr int kShadowMapUnit = 10;

// ECEF -> the sphere space of the shaders (z scaled by a/b).
glm::dvec3 toSphereSpace(const glm::dvec3& ecef) {
    return {ecef.x, ecef.y, ecef.z * (Ellipsoid::kSemiMajorAxis / Ellipsoid::kSemiMinorAxis)};
}

}  // namespace

ShadingPass::~ShadingPass() = default;

Result<std::unique_ptr<ShadingPass>> ShadingPass::create(const ShaderLibrary& library) {
    std::unique_ptr<ShadingPass> pass(new ShadingPass());
    Result<ShaderProgram> program = ShaderProgram::create(
        library,
        {{GL_VERTEX_SHADER, "common/fullscreen.vert"}, {GL_FRAGMENT_SHADER, "shading/shade.frag"}});
    if (!program) {
        return program.error();
    }
    pass->program_ = std::move(program.value());
    Result<std::unique_ptr<AtmosphereLuts>> atmosphere = AtmosphereLuts::create(library);
    if (!atmosphere) {
        return atmosphere.error();
    }
    pass->atmosphere_ = std::move(atmosphere.value());
    pass->emptyVertexArray_ = createGlVertexArray();
    return pass;
}

glm::dvec3 ShadingPass::horizontalIlluminance(const glm::dvec3& pointEcef, const glm::dvec3& sun,
                                              const AtmosphereParameters& parameters) {
    atmosphere_->prepare(parameters);
    const glm::dvec3 point = toSphereSpace(pointEcef);
    const double radius = glm::length(point);
    return atmosphere_->horizontalIlluminance(
        radius, glm::dot(point / radius, glm::normalize(toSphereSpace(sun))));
}

void ShadingPass::run(const Framebuffer& gbuffer, const Framebuffer& target, const Camera& camera,
                      const glm::dmat4& projection, double near, const ShadingSettings& settings) {
    const glm::dmat3 view = camera.viewRotation();
    atmosphere_->prepare(settings.atmosphereParameters);
    if (settings.atmosphere) {
        AtmosphereView frame;
        frame.cameraSphere = toSphereSpace(camera.position);
        frame.viewToEcef = glm::transpose(view);
        frame.projectionScale = {projection[0][0], projection[1][1]};
        frame.sunSphere = glm::normalize(toSphereSpace(settings.sunDirection));
        frame.shadowMaps = settings.shadowedInscattering ? settings.shadowMaps : nullptr;
        atmosphere_->updateView(frame);
    }
    target.bind();
    glDisable(GL_DEPTH_TEST);
    program_.use();
    program_.setInt("uAlbedo", 0);
    program_.setInt("uNormal", 1);
    program_.setInt("uDepth", 2);
    program_.setVec2("uProjectionScale",
                     glm::vec2(float(projection[0][0]), float(projection[1][1])));
    program_.setVec2("uProjectionOffset",
                     glm::vec2(float(projection[2][0]), float(projection[2][1])));
    program_.setFloat("uNear", float(near));
    program_.setMat3("uViewToEcef", glm::mat3(glm::transpose(view)));
    program_.setVec3("uCameraEcef", glm::vec3(camera.position));
    program_.setVec3("uSunView", glm::vec3(glm::normalize(view * settings.sunDirection)));
    program_.setVec3("uSunEcef", glm::vec3(glm::normalize(settings.sunDirection)));
    program_.setInt("uAtmosphere", settings.atmosphere ? 1 : 0);
    program_.setFloat("uExposure", float(settings.exposure));
    program_.setInt("uSunVisibilityOutput", settings.sunVisibilityOutput ? 1 : 0);
    glBindTextureUnit(0, gbuffer.colorTexture(0));
    glBindTextureUnit(1, gbuffer.colorTexture(1));
    glBindTextureUnit(2, gbuffer.depthTexture());
    atmosphere_->bind(program_, 3);
    program_.setInt("uAmbientOcclusion", kAmbientOcclusionUnit);
    program_.setInt("uHasAmbientOcclusion", settings.ambientOcclusion != 0 ? 1 : 0);
    glBindTextureUnit(kAmbientOcclusionUnit, settings.ambientOcclusion);
    ShadowMaps::bindUniforms(program_, settings.shadowMaps, kShadowMapUnit);
    glBindVertexArray(emptyVertexArray_.get());
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
}

}  // namespace sylva::render
