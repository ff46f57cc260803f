// ShadowMaps: the sun's cascaded shadow maps (seed 001 §7.1) as one depth texture array
// (GL_DEPTH_COMPONENT32F, one layer per cascade, compare mode on, nearest: shadows.glsl
// filters with its own per-texel references). render() fits
// the cascades (ShadowCascades), then lets every ShadowCaster draw each layer.
//
// Needs a current GL 4.5 context for create() and render(); destroy it while that
// context is current. create() fails with an Error naming the missing feature when the
// driver cannot make the depth array or its framebuffer.
#pragma once

#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "sylva/core/base/Result.h"
#include "sylva/render/gl/GlHandle.h"
#include "sylva/render/gl/ShaderProgram.h"
#include "sylva/render/shadows/ShadowCaster.h"

namespace sylva::render {

class ShadowMaps {
public:
    static constexpr int kMaxCascades = 5;  // 4 split cascades + the terrain cascade

    static Result<std::unique_ptr<ShadowMaps>> create();

    // Fits the cascades to `camera` and draws them: terrain casters get every cascade,
    // the others all but the terrain-only one (ShadowCaster::drawShadow decides).
    // Leaves the clip control at zero-to-one and no framebuffer bound.
    Status render(const Camera& camera, double aspect, const glm::dvec3& sunDirection,
                  const ShadowSettings& settings, const std::vector<ShadowCaster*>& casters);

    // The cascades of the last render() (empty: shadows off).
    const std::vector<ShadowCascade>& cascades() const { return cascades_; }
    // Per cascade: camera-relative ECEF metres -> shadow clip (projection × lightRotation).
    std::vector<glm::mat4> shadowMatrices() const;
    std::uint32_t texture() const { return texture_.get(); }
    const glm::dmat3& lightRotation() const { return lightRotation_; }
    int resolution() const { return resolution_; }

    // Sets the uniforms of shaders/shading/shadows.glsl in `program` (any stage that
    // includes it: the shading pass, the aerial-perspective compute pass) and binds the
    // depth array to `textureUnit`. `maps` null or without cascades: uShadowCascadeCount
    // 0, so shadows.glsl answers "lit" without sampling.
    static void bindUniforms(ShaderProgram& program, const ShadowMaps* maps, int textureUnit);

private:
    ShadowMaps() = default;
    Status ensureTexture(int resolution);

    GlTexture texture_;
    GlFramebuffer framebuffer_;
    int resolution_ = 0;
    glm::dmat3 lightRotation_{1.0};
    std::vector<ShadowCascade> cascades_;
};

}  // namespace sylva::render
