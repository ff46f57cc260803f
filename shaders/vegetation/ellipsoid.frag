#version 450 core
// Ray-cast ellipsoid fragment (seed 001 §6.4.1): intersection in the unit-sphere frame,
// relative to the centre; depth from the hit (reversed-Z: near / distance along -z),
// declared depth_less because the hit is never nearer than the quad; the noise alpha
// test of §3.4.1 with its cell count limited by the screen-space derivative (the mip
// level fwidth allows); normal perturbed by the noise; screen-door LoD fades.
#include "vegetation.glsl"

layout(location = 0) in vec3 vLocalOrigin;
layout(location = 1) in vec3 vLocalDirection;
layout(location = 2) in vec3 vQuadView;
layout(location = 3) flat in mat3 vLocalToViewNormal;
layout(location = 6) flat in vec4 vColorAo;
layout(location = 7) flat in vec4 vFadeNoise;
layout(location = 8) flat in uvec2 vSeedDither;

uniform float uNear;
uniform float uNormalNoise;  // strength of the normal perturbation

layout(location = 0) out vec4 outAlbedo;  // rgb: linear albedo, a: ambient occlusion
layout(location = 1) out vec4 outNormal;  // xyz: view-space normal, w: material (0)
layout(depth_less) out float gl_FragDepth;

void main() {
    // Closest approach of the ray to the centre, then back along the ray to the surface.
    float a = dot(vLocalDirection, vLocalDirection);
    float along = -dot(vLocalOrigin, vLocalDirection) / a;
    vec3 closest = vLocalOrigin + along * vLocalDirection;
    float discriminant = 1.0 - dot(closest, closest);
    float back = sqrt(max(discriminant, 0.0) / a);
    vec3 q = closest - back * vLocalDirection;  // hit point on the unit sphere
    float t = along - back;                      // ray: quad point × (1 + t)
    // Derivatives before any discard (they need the whole pixel quad).
    vec3 width = fwidth(q);
    float footprint = max(max(width.x, width.y), width.z);
    if (discriminant < 0.0 || t < -1.0) {
        discard;
    }
    float dither = ditherValue(gl_FragCoord.xy, uintBitsToFloat(vSeedDither.y));
    if (dither >= vFadeNoise.x || dither < vFadeNoise.y) {
        discard;
    }
    // Noise cells: the stored level, capped where a cell would be under ~2 pixels.
    float cells = vFadeNoise.z;
    if (footprint > 0.0) {
        cells = min(cells, exp2(floor(log2(max(1.0 / footprint, 1.0)))));
    }
    q = clamp(q, -1.0, 1.0);
    if (vFadeNoise.w > 0.0 && ellipsoidNoise(q, cells, vSeedDither.x) < vFadeNoise.w) {
        discard;
    }
    vec3 hit = vQuadView * (1.0 + t);
    gl_FragDepth = uNear / max(-hit.z, uNear);
    vec3 perturb = vec3(ellipsoidNoise(q, cells, vSeedDither.x ^ 0x68E31DA4u),
                        ellipsoidNoise(q, cells, vSeedDither.x ^ 0xB5297A4Du),
                        ellipsoidNoise(q, cells, vSeedDither.x ^ 0x1B56C4E9u)) - 0.5;
    vec3 normal = normalize(vLocalToViewNormal * normalize(q + uNormalNoise * perturb));
    if (dot(normal, hit) > 0.0) {
        normal = -normal;
    }
    outAlbedo = vColorAo;
    outNormal = vec4(normal, 0.0);
}
