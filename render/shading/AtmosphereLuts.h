// AtmosphereLuts: the GPU look-up tables of the physical atmosphere (Hillaire 2020, "A
// Scalable and Production Ready Sky and Atmosphere Rendering Technique", EGSR):
// transmittance (256x64), multiple scattering Psi_ms (32x32) and sky irradiance of a
// horizontal surface (64x16), computed once per AtmosphereParameters; and per frame the
// sky-view LUT (192x108) for the camera's radius and the aerial-perspective froxel
// volume (64x36 columns x 64 slices, in-scattering and transmittance) for the camera's
// frustum, its single scattering shadowed by the sun's shadow maps. All compute shaders
// (shaders/shading/atmosphere_*.comp); units per unit sun illuminance. Needs a current GL 4.5
// context; private to render/shading.
#pragma once

#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "sylva/core/atmosphere/AtmosphereParameters.h"
#include "sylva/core/base/Result.h"
#include "sylva/render/gl/GlHandle.h"
#include "sylva/render/gl/ShaderLibrary.h"
#include "sylva/render/gl/ShaderProgram.h"
#include "sylva/render/shadows/ShadowMaps.h"

namespace sylva::render {

// What the per-frame tables depend on; sphere space (ECEF with z scaled by a/b).
struct AtmosphereView {
    glm::dvec3 cameraSphere{0.0};  // metres
    glm::dmat3 viewToEcef{1.0};
    glm::dvec2 projectionScale{1.0};  // projection[0][0], projection[1][1]
    glm::dvec3 sunSphere{1, 0, 0};    // unit
    // The sun's shadow maps drawn for this camera (not owned): single scattering in the
    // aerial-perspective volume is shadowed by them (atmosphere_shadow_hook.glsl). Null:
    // the air is lit everywhere.
    const ShadowMaps* shadowMaps = nullptr;
};

class AtmosphereLuts {
public:
    static Result<std::unique_ptr<AtmosphereLuts>> create(const ShaderLibrary& library);

    // Recomputes the per-parameter tables when `parameters` differ from the last call.
    void prepare(const AtmosphereParameters& parameters);
    // The per-frame tables (after prepare).
    void updateView(const AtmosphereView& view);
    // Sets the atmosphere's parameter uniforms and samplers of the shading program and
    // binds the tables to texture units firstUnit .. firstUnit + 5.
    void bind(ShaderProgram& program, int firstUnit) const;

    // Illuminance (lux, linear RGB) of a horizontal surface at `radius` metres from the
    // centre with the sun at cosine `sunZenithCos`: the direct sun through the
    // atmosphere plus the sky irradiance table (read back once per parameters).
    glm::dvec3 horizontalIlluminance(double radius, double sunZenithCos) const;

    static void setParameterUniforms(ShaderProgram& program, const AtmosphereParameters& p);
    static constexpr glm::ivec3 kFroxels{64, 36, 64};

private:
    AtmosphereLuts() = default;
    // Aerial-perspective slice mapping of a frame: the near scale and the range (metres).
    glm::dvec2 aerialMapping(const glm::dvec3& cameraSphere) const;

    ShaderProgram transmittanceProgram_, multipleScatteringProgram_, irradianceProgram_,
        skyViewProgram_, aerialProgram_;
    GlTexture transmittance_, multipleScattering_, irradiance_, skyView_, aerialInscattered_,
        aerialTransmittance_;
    AtmosphereParameters parameters_;
    bool prepared_ = false;
    glm::dvec2 aerial_{100.0, 1.0e6};
    std::vector<float> irradianceTable_;  // IRRADIANCE_SIZE RGBA, per unit sun illuminance
};

}  // namespace sylva::render
