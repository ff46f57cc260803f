#version 450 core
// Ray-cast ellipsoid depth for the sun's shadow map (orthographic: the ray through a
// texel runs along the light's -z from the ellipsoid's top). The LoD's noise alpha test
// (§3.4.1: front hit, then the back hit where the front is perforated, as
// PrimitiveRasterizer calibrated it; the level's cells; the level's shadow threshold from
// core/plantlod/ShadowThresholds, so every level covers what the leaves cover seen from
// the sun's heights) perforates the crown, so the filtered shadow lookup sees the crown's
// transmittance; the screen-door fades of the LoD transitions apply as in the G-buffer
// pass.
#include "../vegetation/vegetation.glsl"

layout(location = 0) flat in mat3 vToLocal;
layout(location = 3) flat in vec4 vLocalCenterTop;
layout(location = 4) flat in vec4 vFadeNoise;
layout(location = 5) flat in uvec2 vSeedDither;

uniform mat4 uProjection;
uniform vec2 uViewport;  // texels

layout(depth_greater) out float gl_FragDepth;

void main() {
    vec2 ndc = gl_FragCoord.xy / uViewport * 2.0 - 1.0;
    vec2 xy = (ndc - vec2(uProjection[3][0], uProjection[3][1])) /
              vec2(uProjection[0][0], uProjection[1][1]);
    vec3 origin = vToLocal * vec3(xy, vLocalCenterTop.w) - vLocalCenterTop.xyz;
    vec3 direction = -vToLocal[2];  // toLocal × (0, 0, -1)
    float a = dot(direction, direction);
    float b = dot(origin, direction);
    float h = b * b - a * (dot(origin, origin) - 1.0);
    float t = (-b - sqrt(max(h, 0.0))) / a;
    vec3 q = origin + t * direction;
    if (h < 0.0) {
        discard;
    }
    float dither = ditherValue(gl_FragCoord.xy, uintBitsToFloat(vSeedDither.y));
    if (dither >= vFadeNoise.x || dither < vFadeNoise.y) {
        discard;
    }
    // The level's own cells, not capped at the texel size as the image pass caps them
    // against aliasing: point samples of white noise keep its mean, and the PCF lookup
    // filters the pattern, whereas fewer cells per diameter put the front and back hits
    // of a ray into the same cell, so one test decided both and the crown's opacity
    // varied with its size in texels (lighter crowns at the 3-texel shadow level).
    float cells = vFadeNoise.z;
    if (vFadeNoise.w > 0.0 && ellipsoidNoise(clamp(q, -1.0, 1.0), cells, vSeedDither.x) < vFadeNoise.w) {
        // Perforated front: test the back hit too, as the image pass and the LoD's
        // calibration (PrimitiveRasterizer) do; one test let 1 − t of the light through
        // where the level was calibrated to 1 − t², i.e. coarse levels were ~40 % more
        // transparent than the fine ones (docs/benchmarks.md, shading).
        t = (-b + sqrt(max(h, 0.0))) / a;
        q = origin + t * direction;
        if (ellipsoidNoise(clamp(q, -1.0, 1.0), cells, vSeedDither.x) < vFadeNoise.w) {
            discard;
        }
    }
    gl_FragDepth = uProjection[2][2] * (vLocalCenterTop.w - t) + uProjection[3][2];
}
