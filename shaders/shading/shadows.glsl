// Sun shadows from the cascaded shadow maps (seed 001 §7.1; ShadowMaps, ShadowCascades).
// Positions are camera-relative ECEF metres (as the shading pass reconstructs them from
// the depth buffer). The cascades are tried in order (finest first, the terrain-only
// cascade last); the first whose box holds the point and its filter footprint answers.
//
// Bias without acne or peter-panning, at any sun elevation: the filter compares every
// shadow-map texel with the receiver's own plane extrapolated to that texel's centre
// (receiver-plane depth bias: the plane's depth gradient in light space comes from the
// normal, ∂depth/∂x = n_x / n_z per metre), so a grazing sun, whose texels each span many
// metres of depth on the ground, needs no large constant bias. What remains is a small bias
// for curvature and for the shadow pass drawing coarser terrain: 0.5 + tan(θ) / 10 texels
// of depth (θ between normal and sun, tan θ at most 12). No normal offset: lifting the
// receiver moves a shadow's outline by the lift / tan(elevation) (a pole's shadow grew
// 2 % shorter with a three-texel offset), while a depth bias does not move it (the
// caster's edge lies far from the receiver in depth).
//
// Curved receivers: the filter's taps reach 1.5 texels across the light's view, which on
// ground the sun grazes is 1.5 texels / cos θ along the ground (60 m for 4 m texels at a
// 5° sun). A concave receiver (a valley floor, the foot of a slope) rises above its
// tangent plane there by ½ κ s² (κ its curvature, s the tap's distance along the ground),
// and the taps saw the receiver's own ground as an occluder: whole valley floors and the
// far ends of ridge shadows were half shadowed although the sun reached them (Olinda,
// ShadowTest: 741 of 23,909 pixels shaded that a CPU ray march finds lit, all rays within
// 2–8 m of the ground). Each tap's reference is lowered by that rise in depth units,
// ½ κ |o|² texel² / cos² θ / cos θ (o: the tap's offset in texels; a rise along the normal
// moves the surface 1 / cos θ towards the sun); κ comes from the shading pass (the
// G-buffer's neighbouring normals, concave part only), 0 for planar receivers.
//
// Filtering: a 3 × 3-texel box of bilinear percentage-closer lookups, done as 4 × 4 single
// texel comparisons with the box's weights (each texel against its own plane depth), so
// an edge fades over about three texels.
#ifndef SHADOWS_GLSL
#define SHADOWS_GLSL

#define MAX_SHADOW_CASCADES 5
uniform sampler2DArrayShadow uShadowMap;
uniform int uShadowCascadeCount;  // 0: shadows off (visibility 1 everywhere)
uniform mat4 uShadowMatrices[MAX_SHADOW_CASCADES];  // camera-relative ECEF -> shadow clip
uniform float uShadowTexelSizes[MAX_SHADOW_CASCADES];  // metres per texel
uniform float uShadowDepthBias[MAX_SHADOW_CASCADES];   // depth units (one texel)
uniform float uShadowResolution;                       // texels per side
uniform mat3 uShadowLightRotation;                     // ECEF -> light frame (+z: the sun)

// The shadow clip position of `position` in `cascade` and whether it lies inside with a
// margin of `margin` texels.
bool shadowCoordinate(vec3 position, int cascade, float margin, out vec3 coordinate) {
    vec4 clip = uShadowMatrices[cascade] * vec4(position, 1.0);
    coordinate = vec3(clip.xy * 0.5 + 0.5, clip.z);
    float limit = 1.0 - 2.0 * margin / uShadowResolution;
    return all(lessThan(abs(clip.xy), vec2(limit))) && clip.z >= 0.0 && clip.z <= 1.0;
}

// `gradient`: the receiver plane's depth change per texel in x and y (depth units);
// `bias`: depth units towards the sun; `curvatureDepth`: the receiver's rise above its
// plane per squared texel of offset (depth units).
float shadowFiltered(vec3 coordinate, int cascade, vec2 gradient, float bias,
                     float curvatureDepth) {
    vec2 position = coordinate.xy * uShadowResolution - 0.5;  // texel centres at integers
    vec2 base = floor(position);
    vec2 f = position - base;
    vec4 weightX = vec4(1.0 - f.x, 1.0, 1.0, f.x);
    vec4 weightY = vec4(1.0 - f.y, 1.0, 1.0, f.y);
    float sum = 0.0;
    for (int j = 0; j < 4; ++j) {
        for (int i = 0; i < 4; ++i) {
            vec2 tap = vec2(float(i - 1), float(j - 1));
            vec2 offset = tap - f;  // texels from the receiver
            float reference =
                coordinate.z - bias + dot(offset, gradient) - curvatureDepth * dot(offset, offset);
            vec2 uv = (base + tap + 0.5) / uShadowResolution;
            sum += weightX[i] * weightY[j] * texture(uShadowMap, vec4(uv, float(cascade), reference));
        }
    }
    return sum / 9.0;
}

// Visibility of the sun (0 = in shadow, 1 = lit) at a surface point with unit normal
// `normalEcef` and concave curvature `curvature` (1 / metres, 0: planar or convex).
float sunVisibility(vec3 position, vec3 normalEcef, float curvature) {
    if (uShadowCascadeCount == 0) {
        return 1.0;
    }
    vec3 normalLight = uShadowLightRotation * normalEcef;
    float cosine = clamp(normalLight.z, 0.08, 1.0);
    float sine = sqrt(1.0 - cosine * cosine);
    vec2 slope = normalLight.xy / cosine;  // receiver plane: metres of depth per metre
    for (int cascade = 0; cascade < uShadowCascadeCount; ++cascade) {
        vec3 coordinate;
        if (shadowCoordinate(position, cascade, 3.0, coordinate)) {
            float texelDepth = uShadowDepthBias[cascade];  // one texel of metres, depth units
            float curvatureDepth = 0.5 * curvature * uShadowTexelSizes[cascade] * texelDepth /
                                   (cosine * cosine * cosine);
            return shadowFiltered(coordinate, cascade, slope * texelDepth,
                                  texelDepth * (0.5 + 0.1 * (sine / cosine)), curvatureDepth);
        }
    }
    return 1.0;
}

// Visibility of the sun at a point in the air (no surface, no normal offset): the term
// for shadowed in-scattering along a view ray (seed 001 §7.2, light shafts).
float sunVisibilityInAir(vec3 position) {
    for (int cascade = 0; cascade < uShadowCascadeCount; ++cascade) {
        vec3 coordinate;
        if (shadowCoordinate(position, cascade, 1.0, coordinate)) {
            return texture(uShadowMap, vec4(coordinate.xy, float(cascade), coordinate.z));
        }
    }
    return 1.0;
}

#endif
