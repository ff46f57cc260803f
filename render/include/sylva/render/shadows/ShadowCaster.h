// ShadowCaster: what draws into the sun's shadow maps. The terrain, the vegetation and
// any later renderer (meshes, buildings and objects of issue 17) implement
// `drawShadow` and are handed to the SceneRenderer (RenderSettings::shadowCasters for
// renderers it does not own); ShadowMaps calls every caster once per cascade with the
// cascade's depth layer bound, cleared and the state set (depth test LESS, depth clamp,
// zero-to-one clip control, no colour attachments).
//
// A caster draws depth only: it transforms its geometry to camera-relative ECEF metres
// (its ECEF position minus `ShadowView::camera.position`, computed in double and then cast
// to float, like the G-buffer passes), rotates it by `lightRotation` and applies
// `projection` (orthographic: every ray runs parallel to the sun). Alpha-tested
// geometry discards where it is transparent; partly transparent casters (tree crowns)
// discard stochastically (a stable dither) with their opacity, so the filtered lookup
// sees their transmittance. A caster must not change the bound framebuffer or viewport.
#pragma once

#include <cstdint>
#include <optional>

#include <glm/glm.hpp>

#include "sylva/core/scene/Camera.h"
#include "sylva/render/shadows/ShadowCascades.h"

namespace sylva::render {

struct ShadowView {
    const Camera* camera = nullptr;          // the viewer (not the light)
    glm::dmat3 lightRotation{1.0};           // ECEF -> light frame (+z towards the sun)
    glm::dmat4 projection{1.0};              // light-rotated camera-relative -> clip
    glm::dvec3 sunDirection{0.0, 0.0, 1.0};  // ECEF unit vector towards the sun
    const ShadowCascade* cascade = nullptr;  // extent, texel size (metres), terrainOnly
    int cascadeIndex = 0;
    int resolution = 0;  // texels per side
};

class ShadowCaster {
public:
    virtual ~ShadowCaster() = default;
    // Draws this caster's depth for one cascade. Casters that are not terrain skip
    // cascades with `cascade->terrainOnly` set.
    virtual void drawShadow(const ShadowView& view) = 0;
    // Casters whose depth in a cascade depends only on the cascade's Earth-fixed box and
    // on a state of their own (the terrain: its levels and clipmap contents) return a key
    // of that state; ShadowMaps then keeps their depth of the cascade and draws them
    // again only when the box or the key changes. nullopt (the default): drawn every time.
    virtual std::optional<std::uint64_t> shadowCacheKey(const ShadowView& view) const {
        (void)view;
        return std::nullopt;
    }
};

}  // namespace sylva::render
