#version 450 core
// Ray-cast tapered capsule (seed 001 §6.4.2): the ray starts at the quad point and the
// line is described relative to its start, so no term grows with the camera distance.
// The body is a cylinder whose radius follows the taper at the hit (two fixed-point
// steps), closed by spheres of the end radii.
#include "vegetation.glsl"

layout(location = 0) in vec3 vFromStart;
layout(location = 1) in vec3 vDirection;
layout(location = 2) flat in vec4 vAxisRadius;
layout(location = 3) flat in vec4 vColorAo;
layout(location = 4) flat in vec4 vFadeEnd;

uniform float uNear;

layout(location = 0) out vec4 outAlbedo;
layout(location = 1) out vec4 outNormal;

// Ray o + t d against a sphere at c; returns t or -1.
float sphereHit(vec3 o, vec3 d, vec3 c, float r) {
    vec3 oc = o - c;
    float a = dot(d, d), b = dot(oc, d), k = dot(oc, oc) - r * r;
    float h = b * b - a * k;
    return h < 0.0 ? -1.0 : (-b - sqrt(h)) / a;
}

void main() {
    float dither = ditherValue(gl_FragCoord.xy, vFadeEnd.w);
    if (dither >= vFadeEnd.x || dither < vFadeEnd.y) {
        discard;
    }
    vec3 o = vFromStart, d = vDirection, ba = vAxisRadius.xyz;
    float r0 = vAxisRadius.w, r1 = vFadeEnd.z;
    float baba = dot(ba, ba), bard = dot(ba, d), baoc = dot(ba, o);
    float k2 = baba * dot(d, d) - bard * bard;
    float k1 = baba * dot(o, d) - baoc * bard;
    // The capsule is the union of the body and the end spheres: its first hit is the
    // nearest first hit of the three (the ray starts outside all of them).
    const float kMiss = 1e30;
    float best = kMiss;
    vec3 normal = vec3(0.0, 0.0, 1.0);
    // Body: a cylinder whose radius is the taper's at the hit (one refinement step).
    float radius = max(r0, r1);
    for (int step = 0; step < 2 && k2 > 0.0; ++step) {
        float k0 = baba * dot(o, o) - baoc * baoc - radius * radius * baba;
        float h = k1 * k1 - k2 * k0;
        if (h < 0.0) {
            break;
        }
        float t = (-k1 - sqrt(h)) / k2;
        float y = (baoc + t * bard) / baba;
        radius = mix(r0, r1, clamp(y, 0.0, 1.0));
        if (step == 1 && y >= 0.0 && y <= 1.0) {
            best = t;
            normal = (o + t * d - ba * y) / max(radius, 1e-9);
        }
    }
    float ts = sphereHit(o, d, vec3(0.0), r0);
    if (ts > -1.0 && ts < best) {
        best = ts;
        normal = o + ts * d;
    }
    float te = sphereHit(o, d, ba, r1);
    if (te > -1.0 && te < best) {
        best = te;
        normal = o + te * d - ba;
    }
    if (best == kMiss) {
        discard;
    }
    vec3 hit = d * (1.0 + best);
    gl_FragDepth = uNear / max(-hit.z, uNear);
    normal = normalize(normal);
    outAlbedo = vColorAo;
    outNormal = vec4(normal, 0.0);
}
