// Ray against a tapered capsule (seed 001 §6.4.2), shared by the G-buffer pass
// (line.frag) and the shadow maps (shadows/line_shadow.frag): the line from the origin
// to `ba` with radii r0 at the start and r1 at the end; the ray o + t d starts outside.
// The body is a cylinder whose radius follows the taper at the hit (two fixed-point
// steps), closed by spheres of the end radii. Returns the ray parameter of the first hit
// (1e30: miss) and the unnormalised normal there.
#ifndef CAPSULE_GLSL
#define CAPSULE_GLSL

// Ray o + t d against a sphere at c; returns t or -1.
float sphereHit(vec3 o, vec3 d, vec3 c, float r) {
    vec3 oc = o - c;
    float a = dot(d, d), b = dot(oc, d), k = dot(oc, oc) - r * r;
    float h = b * b - a * k;
    return h < 0.0 ? -1.0 : (-b - sqrt(h)) / a;
}

float capsuleHit(vec3 o, vec3 d, vec3 ba, float r0, float r1, out vec3 normal) {
    float baba = dot(ba, ba), bard = dot(ba, d), baoc = dot(ba, o);
    float k2 = baba * dot(d, d) - bard * bard;
    float k1 = baba * dot(o, d) - baoc * bard;
    // The capsule is the union of the body and the end spheres: its first hit is the
    // nearest first hit of the three (the ray starts outside all of them).
    const float kMiss = 1e30;
    float best = kMiss;
    normal = vec3(0.0, 0.0, 1.0);
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
    return best;
}

#endif
