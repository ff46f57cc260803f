#include "AtmosphereLuts.h"

#include <glad/gl.h>

#include <algorithm>
#include <cmath>

#include "sylva/core/atmosphere/AtmosphereModel.h"

namespace sylva::render {
namespace {

constexpr glm::ivec2 kTransmittanceSize{256, 64};
constexpr glm::ivec2 kMultipleScatteringSize{128, 32};
constexpr glm::ivec2 kIrradianceSize{64, 16};
constexpr glm::ivec2 kSkyViewSize{192, 108};
// The aerial-perspective pass's texture units: 0-1 the LUTs, then the shadow maps.
constexpr int kAerialShadowMapUnit = 2;

GlTexture texture2d(glm::ivec2 size) {
    GlTexture texture = createGlTexture(GL_TEXTURE_2D);
    glTextureStorage2D(texture.get(), 1, GL_RGBA32F, size.x, size.y);
    glTextureParameteri(texture.get(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(texture.get(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(texture.get(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(texture.get(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return texture;
}

GlTexture texture3d(glm::ivec3 size) {
    GlTexture texture = createGlTexture(GL_TEXTURE_3D);
    glTextureStorage3D(texture.get(), 1, GL_RGBA32F, size.x, size.y, size.z);
    glTextureParameteri(texture.get(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(texture.get(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(texture.get(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(texture.get(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTextureParameteri(texture.get(), GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
    return texture;
}

GLuint groups(int size) {
    return GLuint((size + 7) / 8);
}

}  // namespace

Result<std::unique_ptr<AtmosphereLuts>> AtmosphereLuts::create(const ShaderLibrary& library) {
    std::unique_ptr<AtmosphereLuts> luts(new AtmosphereLuts());
    struct Entry {
        ShaderProgram* program;
        const char* path;
    };
    for (const Entry& entry :
         {Entry{&luts->transmittanceProgram_, "shading/atmosphere_transmittance.comp"},
          Entry{&luts->multipleScatteringProgram_, "shading/atmosphere_multiple_scattering.comp"},
          Entry{&luts->irradianceProgram_, "shading/atmosphere_irradiance.comp"},
          Entry{&luts->skyViewProgram_, "shading/atmosphere_sky_view.comp"},
          Entry{&luts->aerialProgram_, "shading/atmosphere_aerial_perspective.comp"}}) {
        Result<ShaderProgram> program =
            ShaderProgram::create(library, {{GL_COMPUTE_SHADER, entry.path}});
        if (!program) {
            return program.error();
        }
        *entry.program = std::move(program.value());
    }
    luts->transmittance_ = texture2d(kTransmittanceSize);
    luts->multipleScattering_ = texture2d(kMultipleScatteringSize);
    luts->irradiance_ = texture2d(kIrradianceSize);
    luts->skyView_ = texture2d(kSkyViewSize);
    luts->aerialInscattered_ = texture3d(kFroxels);
    luts->aerialTransmittance_ = texture3d(kFroxels);
    return luts;
}

void AtmosphereLuts::setParameterUniforms(ShaderProgram& program, const AtmosphereParameters& p) {
    program.setFloat("uBottomRadius", float(p.bottomRadius));
    program.setFloat("uTopRadius", float(p.topRadius));
    program.setVec3("uRayleighScattering", glm::vec3(p.rayleighScattering));
    program.setFloat("uRayleighScaleHeight", float(p.rayleighScaleHeight));
    program.setFloat("uMieScattering", float(p.mieScattering));
    program.setFloat("uMieExtinction", float(p.mieExtinction));
    program.setFloat("uMieScaleHeight", float(p.mieScaleHeight));
    program.setFloat("uMieAsymmetry", float(p.mieAsymmetry));
    program.setVec3("uOzoneAbsorption", glm::vec3(p.ozoneAbsorption));
    program.setFloat("uOzoneCentre", float(p.ozoneCentre));
    program.setFloat("uOzoneHalfWidth", float(p.ozoneHalfWidth));
    program.setFloat("uGroundAlbedo", float(p.groundAlbedo));
    program.setFloat("uSunAngularRadius", float(p.sunAngularRadius));
}

void AtmosphereLuts::prepare(const AtmosphereParameters& parameters) {
    if (prepared_ && parameters == parameters_) {
        return;
    }
    parameters_ = parameters;
    prepared_ = true;
    for (ShaderProgram* program : {&transmittanceProgram_, &multipleScatteringProgram_,
                                   &irradianceProgram_, &skyViewProgram_, &aerialProgram_}) {
        setParameterUniforms(*program, parameters);
        program->setInt("uTransmittanceLut", 0);
        program->setInt("uMultipleScatteringLut", 1);
    }
    glBindImageTexture(0, transmittance_.get(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    transmittanceProgram_.use();
    glDispatchCompute(groups(kTransmittanceSize.x), groups(kTransmittanceSize.y), 1);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    glBindTextureUnit(0, transmittance_.get());
    glBindImageTexture(0, multipleScattering_.get(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    multipleScatteringProgram_.use();
    glDispatchCompute(groups(kMultipleScatteringSize.x), groups(kMultipleScatteringSize.y), 1);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    glBindTextureUnit(1, multipleScattering_.get());
    glBindImageTexture(0, irradiance_.get(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    irradianceProgram_.use();
    glDispatchCompute(groups(kIrradianceSize.x), groups(kIrradianceSize.y), 1);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
    irradianceTable_.assign(std::size_t(kIrradianceSize.x) * kIrradianceSize.y * 4, 0.0f);
    glGetTextureImage(irradiance_.get(), 0, GL_RGBA, GL_FLOAT,
                      GLsizei(irradianceTable_.size() * sizeof(float)), irradianceTable_.data());
    glUseProgram(0);
}

glm::dvec2 AtmosphereLuts::aerialMapping(const glm::dvec3& cameraSphere) const {
    const double bottom = parameters_.bottomRadius;
    const double top = parameters_.topRadius;
    const double radius = glm::length(cameraSphere);
    const double topHorizon = std::sqrt((top - bottom) * (top + bottom));
    if (radius >= top) {
        return {10000.0, 2.0 * topHorizon};
    }
    const double horizon = std::sqrt(std::max((radius - bottom) * (radius + bottom), 0.0));
    return {std::clamp(radius - bottom, 100.0, 10000.0), horizon + topHorizon};
}

void AtmosphereLuts::updateView(const AtmosphereView& view) {
    const double radius = glm::length(view.cameraSphere);
    const double viewRadius =
        std::clamp(radius, parameters_.bottomRadius + 1.0, parameters_.topRadius - 10.0);
    glBindTextureUnit(0, transmittance_.get());
    glBindTextureUnit(1, multipleScattering_.get());
    skyViewProgram_.setFloat("uViewRadius", float(viewRadius));
    skyViewProgram_.setFloat("uSunZenithCos",
                             float(glm::dot(view.cameraSphere / radius, view.sunSphere)));
    glBindImageTexture(0, skyView_.get(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    skyViewProgram_.use();
    glDispatchCompute(groups(kSkyViewSize.x), groups(kSkyViewSize.y), 1);

    aerial_ = aerialMapping(view.cameraSphere);
    aerialProgram_.setVec3("uCameraSphere", glm::vec3(view.cameraSphere));
    aerialProgram_.setMat3("uViewToEcef", glm::mat3(view.viewToEcef));
    aerialProgram_.setVec2("uProjectionScale", glm::vec2(view.projectionScale));
    aerialProgram_.setVec3("uSunSphere", glm::vec3(view.sunSphere));
    aerialProgram_.setFloat("uAerialNear", float(aerial_.x));
    aerialProgram_.setFloat("uAerialRange", float(aerial_.y));
    glProgramUniform3i(aerialProgram_.id(), aerialProgram_.uniformLocation("uFroxels"), kFroxels.x,
                       kFroxels.y, kFroxels.z);
    ShadowMaps::bindUniforms(aerialProgram_, view.shadowMaps, kAerialShadowMapUnit);
    glBindImageTexture(0, aerialInscattered_.get(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    glBindImageTexture(1, aerialTransmittance_.get(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    aerialProgram_.use();
    glDispatchCompute(groups(kFroxels.x), groups(kFroxels.y), 1);
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    glUseProgram(0);
}

void AtmosphereLuts::bind(ShaderProgram& program, int firstUnit) const {
    setParameterUniforms(program, parameters_);
    const GlTexture* textures[] = {&transmittance_, &multipleScattering_, &irradiance_,
                                   &skyView_,       &aerialInscattered_,  &aerialTransmittance_};
    const char* names[] = {"uTransmittanceLut", "uMultipleScatteringLut", "uIrradianceLut",
                           "uSkyViewLut",       "uAerialInscattered",     "uAerialTransmittance"};
    for (int i = 0; i < 6; ++i) {
        glBindTextureUnit(GLuint(firstUnit + i), textures[i]->get());
        program.setInt(names[i], firstUnit + i);
    }
    program.setVec3("uSunIlluminance", glm::vec3(float(parameters_.sunIlluminance)));
    program.setFloat("uSunLimbDarkening", float(parameters_.sunLimbDarkening));
    program.setFloat("uAerialNear", float(aerial_.x));
    program.setFloat("uAerialRange", float(aerial_.y));
}

glm::dvec3 AtmosphereLuts::horizontalIlluminance(double radius, double sunZenithCos) const {
    // The sky: bilinear in the read-back irradiance table, on the shader's axes
    // (u = sunZenithCos / 2 + 1/2, v = height / thickness, texel centres at the ends).
    const double u = std::clamp(sunZenithCos * 0.5 + 0.5, 0.0, 1.0) * (kIrradianceSize.x - 1);
    const double v = std::clamp((radius - parameters_.bottomRadius) /
                                    (parameters_.topRadius - parameters_.bottomRadius),
                                0.0, 1.0) *
                     (kIrradianceSize.y - 1);
    const int x0 = std::min(int(u), kIrradianceSize.x - 2);
    const int y0 = std::min(int(v), kIrradianceSize.y - 2);
    const double fx = u - x0, fy = v - y0;
    auto at = [&](int x, int y) {
        const float* p = &irradianceTable_[(std::size_t(y) * kIrradianceSize.x + x) * 4];
        return glm::dvec3(p[0], p[1], p[2]);
    };
    glm::dvec3 sky = (at(x0, y0) * (1 - fx) + at(x0 + 1, y0) * fx) * (1 - fy) +
                     (at(x0, y0 + 1) * (1 - fx) + at(x0 + 1, y0 + 1) * fx) * fy;
    // The sun: its transmittance integrated on the CPU (one ray, exact).
    const AtmosphereModel model(parameters_);
    const glm::dvec3 position(0.0, 0.0, std::max(radius, parameters_.bottomRadius + 1.0));
    const glm::dvec3 sun(std::sqrt(std::max(1.0 - sunZenithCos * sunZenithCos, 0.0)), 0.0,
                         sunZenithCos);
    const glm::dvec3 direct = model.transmittanceToTop(position, sun) * std::max(sunZenithCos, 0.0);
    return (sky + direct) * parameters_.sunIlluminance;
}

}  // namespace sylva::render
