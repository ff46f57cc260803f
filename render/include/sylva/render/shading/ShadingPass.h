// ShadingPass: turns the G-buffer into the final image (seed 001 ch. 7, reduced to
// what the foundation needs): sun and sky light on the terrain, water glint, sky and
// limb glow from a single-scattering atmosphere, aerial perspective (haze), tone
// mapping, sRGB output. The only code that lights anything.
#pragma once

#include <memory>

#include <glm/glm.hpp>

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
    bool atmosphere = true;
    double exposure = 1.0;
    // The sun's cascaded shadow maps drawn for this camera (not owned; null or no
    // cascades: no shadows). Looked up by shaders/shading/shadows.glsl.
    const ShadowMaps* shadowMaps = nullptr;
};

class ShadingPass {
public:
    static Result<std::unique_ptr<ShadingPass>> create(const ShaderLibrary& library);

    // Reads `gbuffer` (attachments 0 albedo, 1 normal, reversed-Z depth) and writes
    // `target` (attachment 0, RGBA8 sRGB-encoded; attachment 1 if present, a float
    // format: linear radiance × exposure, before tone mapping). `near` and `projection` as used
    // to draw the G-buffer.
    void run(const Framebuffer& gbuffer, const Framebuffer& target, const Camera& camera,
             const glm::dmat4& projection, double near, const ShadingSettings& settings);

private:
    ShadingPass() = default;
    void setShadowUniforms(const ShadowMaps* shadowMaps);
    ShaderProgram program_;
    GlVertexArray emptyVertexArray_;  // full-screen triangle: no attributes
};

}  // namespace sylva::render
