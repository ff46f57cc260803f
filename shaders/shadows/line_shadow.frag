#version 450 core
// Ray-cast tapered capsule depth for the sun's shadow map: the ray runs along the light's
// -z from the quad point (capsule.glsl); screen-door fades as in the G-buffer pass.
#include "../vegetation/vegetation.glsl"
#include "../vegetation/capsule.glsl"

layout(location = 0) in vec3 vFromStart;
layout(location = 1) flat in vec4 vAxisRadius;
layout(location = 2) flat in vec4 vFadeEnd;

uniform mat4 uProjection;

layout(depth_greater) out float gl_FragDepth;

void main() {
    float dither = ditherValue(gl_FragCoord.xy, vFadeEnd.w);
    if (dither >= vFadeEnd.x || dither < vFadeEnd.y) {
        discard;
    }
    vec3 normal;
    float t = capsuleHit(vFromStart, vec3(0.0, 0.0, -1.0), vAxisRadius.xyz, vAxisRadius.w,
                         vFadeEnd.z, normal);
    if (t >= 1e30) {
        discard;
    }
    // The quad lies at the capsule's top, so the hit is t metres further from the sun.
    gl_FragDepth = gl_FragCoord.z - uProjection[2][2] * t;
}
