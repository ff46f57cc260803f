// ShadowCascades: where the sun's shadow maps lie (seed 001 §7.1: cascaded shadow maps
// after Zhang et al. 2006, "parallel-split shadow maps"). CPU only, no GL.
//
// The view distance up to `ShadowSettings::distance` is split by the practical split
// scheme (a blend, weight `splitBlend`, of the logarithmic and the uniform split); each
// slice of the camera frustum gets one orthographic light view fitted to the slice's
// bounding sphere, whose size depends only on the splits and the field of view, never
// on the camera's orientation. The light-space centre is snapped to whole texels in
// absolute light coordinates (double), so a moving or turning camera moves the texel
// grid in whole texels only: shadow edges do not shimmer. Each box is `recentreMargin`
// wider than its slice's sphere and its centre is snapped to a coarse Earth-fixed grid
// of whole texels (cells of up to twice the margin), so the box still holds the sphere
// and stays where it is while the camera moves or turns within a cell: its depth can be
// kept across frames (ShadowMaps' cache) instead of being redrawn whenever the camera
// crosses a texel. The boxes depend on the camera alone (no history), so an image does
// not depend on what was rendered before it. One more, coarser cascade
// (`terrainDistance`, terrain only) keeps long mountain shadows beyond the others: a
// ridge 20 km away still shades a valley at dusk.
//
// Frames: "camera-relative" positions are ECEF metres minus the camera's ECEF position
// (the frame the shading pass reconstructs from the depth buffer). The light frame is
// ECEF rotated so that +z points to the sun; `ShadowCascade::projection` maps light-
// rotated camera-relative positions (lightRotation × p) to clip space: x, y in [-1, 1]
// over the cascade, depth 0 on the sun's side of the cascade's sphere and 1 on the far
// side (glClipControl zero-to-one; casters nearer the sun than the box are clamped to 0
// by GL_DEPTH_CLAMP, so they still cast).
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "sylva/core/scene/Camera.h"

namespace sylva::render {

struct ShadowSettings {
    bool enabled = true;
    double distance = 2000.0;          // metres of view distance covered by the split cascades
    int cascades = 4;                  // split cascades (1..4), plus the terrain cascade
    int resolution = 2048;             // texels per side of every cascade
    double splitBlend = 0.9;           // 1: logarithmic splits, 0: uniform
    double firstSplitStart = 1.0;      // metres: where the logarithmic split scheme starts
    double terrainDistance = 60000.0;  // metres: the terrain-only far cascade (0: none)
    // Fraction of each slice's sphere radius added to its box on every side; the box
    // centre snaps to cells of whole texels up to twice that wide, so a camera moving
    // within a cell keeps the box (and its cached depth). 0: the box follows the camera
    // texel by texel (every move of a texel redraws the cascade). Costs (1 + margin)
    // times larger texels.
    double recentreMargin = 0.125;
    // Cascades redrawn per ShadowMaps::render at most when their cached depth is out of
    // date (0: every one). The others keep their last map, re-expressed for the camera
    // (the same Earth-fixed box), until their turn — the finest first, then the longest
    // kept: interactive frames bound the shadow pass (issue 20's frame budget: redraws as
    // plant tiles arrived were 106-177 ms of a 230-380 ms frame), at the price of shadows
    // a few frames late while the view moves. Screenshots and batch images: 0.
    int maximumRedraws = 0;
};

struct ShadowCascade {
    double nearDistance = 0;  // metres of view distance (along the view axis) covered
    double farDistance = 0;
    double radius = 0;               // metres: half the box's width (sphere + margin)
    double sliceRadius = 0;          // metres: the bounding sphere of the slice
    double texelSize = 0;            // metres per shadow-map texel
    double cellSize = 0;             // metres: the grid the box centre snaps to (whole texels)
    bool terrainOnly = false;        // the far cascade: only terrain casts into it
    glm::dvec3 centerRelative{0.0};  // sphere centre, camera-relative ECEF
    glm::dvec3 boxRelative{0.0};     // box centre, camera-relative ECEF
    glm::dvec3 boxLight{0.0};        // the box centre in absolute light coordinates (snapped)
    glm::dmat4 projection{1.0};      // light-rotated camera-relative -> clip (see above)
};

class ShadowCascades {
public:
    // ECEF -> light rotation for `sunDirection` (ECEF unit vector towards the sun): rows
    // are the light's x, y (perpendicular to the sun, fixed for a given sun) and z (the sun).
    static glm::dmat3 lightRotation(const glm::dvec3& sunDirection);

    // Split distances d_0 = 0 < d_1 < ... < d_n = settings.distance (practical scheme).
    static std::vector<double> splits(const ShadowSettings& settings);

    // The cascades for `camera` with the given aspect ratio (width / height): the split
    // cascades, then the terrain cascade when `terrainDistance` > `distance`. Empty when
    // shadows are disabled. The depth range reaches one radius beyond the sphere towards
    // the sun; nearer casters are clamped to depth 0 (see above).
    static std::vector<ShadowCascade> fit(const Camera& camera, double aspect,
                                          const glm::dvec3& sunDirection,
                                          const ShadowSettings& settings);
    // `cascade`, fitted for another camera, seen from `camera` (the same `light`): its
    // Earth-fixed box, depth range and texels unchanged, its camera-relative centres and
    // projection re-expressed — so a map drawn for it stays valid.
    static ShadowCascade reexpressed(const ShadowCascade& cascade, const Camera& camera,
                                     const glm::dmat3& light);
};

}  // namespace sylva::render
