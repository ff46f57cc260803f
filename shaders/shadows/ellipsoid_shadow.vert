#version 450 core
// Ellipsoids into the sun's shadow map (seed 001 §6.4.1 and §7.1): the orthographic
// counterpart of vegetation/ellipsoid.vert. Every ray runs along the light's -z, so the
// ellipsoid's outline is the ellipse of its xy extent: the sprite covers its box
// (±sqrt(S_xx), ±sqrt(S_yy) with S = M Mᵀ) and sits at the depth of the point nearest the
// sun (z + sqrt(S_zz)); the fragment shader casts the ray from there (depth_greater).
// Instances come from LodSelector in the light frame (camera-relative, rotated by the
// light rotation) with the plants' shadow error (VegetationSettings::shadowErrorTexels).
#include "../vegetation/vegetation.glsl"

struct Ellipsoid {
    vec4 centerNoise;  // xyz centre (model, metres), w noise level
    vec4 axis0;        // xyz axis × radius, w alpha threshold
    vec4 axis1;        // xyz axis × radius, w ambient occlusion
    vec4 axis2;        // xyz axis × radius, w error minimum
    vec4 color;        // rgb linear, w error maximum
};
layout(std430, binding = 0) readonly buffer Ellipsoids { Ellipsoid ellipsoids[]; };
// The noise thresholds of each ellipsoid in the shadow pass (core/plantlod/
// ShadowThresholds): its level's thresholds for the leaves' coverage seen 10° (x) and 55°
// (y) above the plant's horizon, instead of the image's axis0.w (calibrated mostly on
// views 10° above the horizon, too transparent seen from higher up).
layout(std430, binding = 2) readonly buffer ShadowThresholds { vec2 shadowThresholds[]; };

layout(location = 0) in vec4 aAxisX;  // w: tolerated error (metres per texel)
layout(location = 1) in vec4 aAxisY;  // w: dither offset
layout(location = 2) in vec4 aAxisZ;
layout(location = 3) in vec4 aOrigin;
layout(location = 4) in vec4 aTint;

uniform mat4 uProjection;  // light frame -> clip, orthographic (ShadowCascade::projection)
uniform float uTexelSize;  // metres per shadow texel
uniform float uBand;
uniform float uMeshError;
uniform float uMaximumPointSize;  // texels: larger sprites go to the quad pass
uniform bool uQuadPass;

layout(location = 0) flat out mat3 vToLocal;      // light frame -> unit-sphere frame
layout(location = 3) flat out vec4 vLocalCenterTop;  // xyz: toLocal × centre, w: top z
layout(location = 4) flat out vec4 vFadeNoise;    // fade min, fade max, noise cells, threshold
layout(location = 5) flat out uvec2 vSeedDither;  // noise seed, dither offset bits

void main() {
    int primitive = uQuadPass ? gl_VertexID / 6 : gl_VertexID;
    Ellipsoid e = ellipsoids[primitive];
    vec2 fade = intervalFade(aAxisX.w, max(e.axis2.w, uMeshError), e.color.w, uBand);
    gl_Position = vec4(2.0, 2.0, 2.0, 1.0);  // culled unless set below
    gl_PointSize = 1.0;
    if (fade.x <= fade.y || uLeafFraction <= 0.0) {
        return;  // faded out, or no leaves (leaf-off)
    }
    mat3 instance = mat3(aAxisX.xyz, aAxisY.xyz, aAxisZ.xyz);
    vec3 center = instance * e.centerNoise.xyz + aOrigin.xyz;
    mat3 shape = instance * mat3(e.axis0.xyz, e.axis1.xyz, e.axis2.xyz);
    mat3 s = shape * transpose(shape);
    vec3 extent = sqrt(max(vec3(s[0][0], s[1][1], s[2][2]), vec3(0.0)));
    float top = center.z + extent.z;
    float depth = uProjection[2][2] * top + uProjection[3][2];
    vec2 middle = (uProjection * vec4(center, 1.0)).xy;
    vec2 halfSize = extent.xy * 1.01 + uTexelSize;  // one texel of margin on either side
    float size = 2.0 * max(halfSize.x, halfSize.y) / uTexelSize;
    if (uQuadPass) {
        if (size <= uMaximumPointSize) {
            return;
        }
        const vec2 corners[6] = vec2[6](vec2(-1, -1), vec2(1, -1), vec2(1, 1), vec2(-1, -1),
                                        vec2(1, 1), vec2(-1, 1));
        vec2 corner = center.xy + halfSize * corners[gl_VertexID % 6];
        gl_Position = vec4((uProjection * vec4(corner, center.z, 1.0)).xy, depth, 1.0);
    } else {
        if (size > uMaximumPointSize) {
            return;
        }
        gl_Position = vec4(middle, depth, 1.0);
        gl_PointSize = size;
    }
    mat3 toLocal = inverse(shape);
    vToLocal = toLocal;
    vLocalCenterTop = vec4(toLocal * center, top);
    // The sun's elevation above the plant's horizon: its up axis (model z) in the light
    // frame, whose +z points to the sun.
    float sunElevation = degrees(asin(clamp(aAxisZ.z / length(aAxisZ.xyz), -1.0, 1.0)));
    vec2 thresholds = shadowThresholds[primitive];
    float threshold = mix(thresholds.x, thresholds.y, clamp((sunElevation - 10.0) / 45.0, 0.0, 1.0));
    vFadeNoise = vec4(fade, exp2(e.centerNoise.w), seasonalThreshold(threshold));
    vSeedDither = uvec2(ellipsoidNoiseSeed(e.centerNoise.xyz), floatBitsToUint(aAxisY.w));
}
