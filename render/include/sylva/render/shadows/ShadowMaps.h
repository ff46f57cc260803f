// ShadowMaps: the sun's cascaded shadow maps (seed 001 §7.1) as one depth texture array
// (GL_DEPTH_COMPONENT32F, one layer per cascade, compare mode on, nearest: shadows.glsl
// filters with its own per-texel references). render() fits
// the cascades (ShadowCascades), then lets every ShadowCaster draw each layer. The depth
// of the casters that give a cache key (ShadowCaster::shadowCacheKey: the terrain) is
// kept per cascade in a second array and copied back while the cascade's Earth-fixed box,
// the sun and their keys stay the same, so a still or moving camera does not redraw the
// terrain and plants into five 2048² maps every frame: a cascade is drawn again when its
// box moves (ShadowSettings::recentreMargin: once per cell of the camera's path) or a
// key changes (docs/benchmarks.md, shadows).
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
    // Cascades of the last render() whose cached casters' depth was copied, not drawn.
    int cachedCascades() const { return cachedCascades_; }
    // Cascades of the last render() left as they were (out of date, over
    // ShadowSettings::maximumRedraws): their last map, re-expressed for the camera.
    int keptCascades() const { return keptCascades_; }
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

    // The casters of one cascade: those with a cache key (and the key of the box, the sun
    // and theirs), the others drawn every time.
    struct CascadeCasters {
        std::uint64_t key = 0;
        std::vector<ShadowCaster*> cached, drawn;
        bool outOfDate = false;  // cached casters whose depth must be drawn again
    };
    CascadeCasters castersOf(std::size_t index, const ShadowView& view,
                             const std::vector<ShadowCaster*>& casters) const;
    // Which out-of-date cascades keep their last map this time (ShadowSettings::
    // maximumRedraws: the finest first, then those kept longest, are redrawn).
    std::vector<bool> cascadesToKeep(const std::vector<CascadeCasters>& work, int maximumRedraws,
                                     bool sameSun) const;
    // Draws cascade `index` (its layer bound, not cleared): the cached casters' depth from
    // cache_ when their key matches, else drawn and kept; then the other casters.
    void drawCascade(std::size_t index, const ShadowView& view, const CascadeCasters& casters);

    GlTexture texture_;
    GlTexture cache_;  // the cached casters' depth per cascade (same format)
    std::uint64_t cacheKeys_[kMaxCascades] = {};
    bool cacheValid_[kMaxCascades] = {};
    int cachedCascades_ = 0;
    int keptCascades_ = 0;
    // The cascades the layers of texture_ were last drawn (or kept) for, and per layer
    // whether it holds a map for them and for how many renders it was kept.
    std::vector<ShadowCascade> previous_;
    glm::dmat3 previousLight_{0.0};
    bool layerValid_[kMaxCascades] = {};
    int keptFor_[kMaxCascades] = {};
    GlFramebuffer framebuffer_;
    int resolution_ = 0;
    glm::dmat3 lightRotation_{1.0};
    std::vector<ShadowCascade> cascades_;
};

}  // namespace sylva::render
