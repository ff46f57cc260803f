#version 450 core
// Ray-cast tapered capsule (seed 001 §6.4.2): the ray starts at the quad point and the
// line is described relative to its start, so no term grows with the camera distance
// (the intersection is in capsule.glsl).
#include "vegetation.glsl"
#include "farfield_fade.glsl"
#include "capsule.glsl"

layout(location = 0) in vec3 vFromStart;
layout(location = 1) in vec3 vDirection;
layout(location = 2) flat in vec4 vAxisRadius;
layout(location = 3) flat in vec4 vColorAo;
layout(location = 4) flat in vec4 vFadeEnd;

uniform float uNear;

layout(location = 0) out vec4 outAlbedo;
layout(location = 1) out vec4 outNormal;

void main() {
    if (farFieldCanopyPixel()) {
        discard;  // the far-field canopy has this pixel (farfield_fade.glsl)
    }
    float dither = ditherValue(gl_FragCoord.xy, vFadeEnd.w);
    if (dither >= vFadeEnd.x || dither < vFadeEnd.y) {
        discard;
    }
    vec3 o = vFromStart, d = vDirection;
    vec3 normal;
    float best = capsuleHit(o, d, vAxisRadius.xyz, vAxisRadius.w, vFadeEnd.z, normal);
    if (best >= 1e30) {
        discard;
    }
    vec3 hit = d * (1.0 + best);
    gl_FragDepth = uNear / max(-hit.z, uNear);
    normal = normalize(normal);
    outAlbedo = vColorAo;
    outNormal = vec4(normal, 2.0);  // material 2: leaves (shade.frag)
}
