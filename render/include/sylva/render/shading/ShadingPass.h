// ShadingPass: turns the G-buffer into the final image (seed 001 ch. 7): sun and sky
// light on the terrain from the physical atmosphere (Hillaire 2020 LUTs, AtmosphereLuts),
// water glint, sky, sun disc and limb, aerial perspective (haze) from the froxel volume,
// exposure, tone mapping, sRGB output. The only code that lights anything.
#pragma once

#include <cstdint>
#include <memory>

#include <glm/glm.hpp>

#include "sylva/core/atmosphere/AtmosphereParameters.h"
#include "sylva/core/base/Result.h"
#include "sylva/core/scene/Camera.h"
#include "sylva/render/gl/Framebuffer.h"
#include "sylva/render/gl/GlHandle.h"
#include "sylva/render/gl/ShaderLibrary.h"
#include "sylva/render/gl/ShaderProgram.h"
#include "sylva/render/shadows/ShadowMaps.h"

namespace sylva::render {

struct ShadingSettings {
    glm::dvec3 sunDirection{1, 0, 0};  // unit vector towards the sun, ECEF
    bool atmosphere = true;  // sky, limb and aerial perspective (the light always uses it)
    AtmosphereParameters atmosphereParameters;
    // Scale from luminance (cd/m^2) to the tone mapper's input: exposureScale(EV100) x
    // the project's exposure factor (SceneRenderer meters EV100).
    double exposure = 1.0 / 40000.0;
    // The sun's cascaded shadow maps drawn for this camera (not owned; null or no
    // cascades: no shadows). Looked up by shaders/shading/shadows.glsl.
    const ShadowMaps* shadowMaps = nullptr;
    // Whether `shadowMaps` also shadow the air (shadowed in-scattering, seed 001 §7.2):
    // single scattering in the aerial perspective only where the sun reaches. Off: the
    // air is lit everywhere (the state before shadowed in-scattering; tests compare).
    bool shadowedInscattering = true;
    // Screen-space ambient occlusion of this G-buffer (AmbientOcclusionPass::run's R16F
    // texture, not owned; 0: none). Multiplies the sky light with the G-buffer's own
    // occlusion (albedo.a); the sun is never occluded by it.
    std::uint32_t ambientOcclusion = 0;
    // Instead of light, writes each surface pixel's sun visibility (0 in shadow .. 1 lit:
    // the filtered shadow-map term the sunlight is multiplied by) as r = g = b, linear and
    // unexposed, in both outputs (the sRGB one without tone mapping); the sky is 1. What
    // the shadows do, measured apart from the sun and sky light (ShadowTest's oracle).
    bool sunVisibilityOutput = false;
};

class AtmosphereLuts;

class ShadingPass {
public:
    ~ShadingPass();
    static Result<std::unique_ptr<ShadingPass>> create(const ShaderLibrary& library);

    // Reads `gbuffer` (attachments 0 albedo, 1 normal, reversed-Z depth) and writes
    // `target` (attachment 0, RGBA8 sRGB-encoded; attachment 1 if present, a float
    // format: linear radiance × exposure, before tone mapping). `near` and `projection` as used
    // to draw the G-buffer.
    void run(const Framebuffer& gbuffer, const Framebuffer& target, const Camera& camera,
             const glm::dmat4& projection, double near, const ShadingSettings& settings);

    // Illuminance (lux, linear RGB) of a horizontal surface at `pointEcef` (metres) from
    // the sun (unit ECEF vector) and the sky of `parameters`: what an incident-light meter
    // there reads. Computes the atmosphere's tables first if needed.
    glm::dvec3 horizontalIlluminance(const glm::dvec3& pointEcef, const glm::dvec3& sun,
                                     const AtmosphereParameters& parameters);

private:
    ShadingPass() = default;
    ShaderProgram program_;
    GlVertexArray emptyVertexArray_;  // full-screen triangle: no attributes
    std::unique_ptr<AtmosphereLuts> atmosphere_;
};

}  // namespace sylva::render
