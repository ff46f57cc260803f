#version 450 core
// Screen-space ambient occlusion (seed 001 §7.1: "for surfaces without associated AO
// value, we compute it on-the-fly based on the G-Buffer using the horizon-based Screen
// Space Ambient Occlusion (SSAO) by Bavoil and Sainz [2008]"), its horizons searched in
// slices round the view vector (Jimenez et al. 2016, "Practical Realtime Strategies for
// Accurate Indirect Occlusion"), so the result is the occluded solid angle whatever the
// view direction.
//
// For each pixel: the surface point P (view space, from the reversed-Z depth), its normal
// n and V = the unit vector from P to the eye. Directions u_k ⟂ V (DIRECTIONS of them,
// evenly spaced in azimuth round V) each span a slice {cos θ V + sin θ u_k}; in polar
// coordinates round V the solid angle is sin θ dθ dψ, so the visible part of the
// hemisphere is (1/2π) ∫ (1 − cos θ_h(ψ)) dψ with θ_h the horizon's angle from V, and
// the occluded fraction (1/2π) ∫ (cos θ_h − cos θ_t) dψ with θ_t the tangent plane's
// angle in the slice (cos θ_t = −n·u / |(n·V, n·u)|; open ground gives exactly 0). The
// horizon is searched in STEPS steps along the slice's screen line out to the projection
// of a sphere of `uRadius` metres round P (×1.25: nearer surfaces project larger); a
// sample S counts only within that sphere (|S − P| ≤ radius: a ridge in front of far
// terrain, or the sky, never occludes) and at least SIN_BIAS (5.7°) above the tangent
// plane (the terrain's facets and the Earth's curvature do not darken open ground); the
// horizon is the largest cos of its angle from V.
//
// The pattern of slice rotations and step offsets repeats every 4 x 4 pixels
// (ambient_occlusion_blur.frag averages it out) and is tied to the pixel, not to the
// sub-pixel shift of an anti-aliasing sample: every sample gets the same noise, so the
// image is deterministic and stable. Output: r = 1 − strength × occluded fraction (1 for
// the sky and where the sphere is under 1.5 pixels: far surfaces).

layout(location = 0) in vec2 vUv;
layout(location = 0) out vec4 outOcclusion;

uniform sampler2D uNormal;  // view-space normal, material in w
uniform sampler2D uDepth;   // reversed-Z: near / distance along -z, 0 = sky
uniform vec2 uProjectionScale;   // projection[0][0], projection[1][1]
uniform vec2 uProjectionOffset;  // projection[2][0], projection[2][1]
uniform float uNear;             // metres
uniform float uRadius;           // metres
uniform float uStrength;         // 0..1
uniform float uMaxPixels;        // the largest screen radius searched

const int DIRECTIONS = 8;
const int STEPS = 12;
const float SIN_BIAS = 0.1;
const float PI = 3.14159265358979;

// Bayer 4 x 4 order: neighbouring pixels get well spread rotations.
const float BAYER[16] = float[16](0.0, 8.0, 2.0, 10.0, 12.0, 4.0, 14.0, 6.0, 3.0, 11.0, 1.0, 9.0,
                                  15.0, 7.0, 13.0, 5.0);

vec3 viewPosition(vec2 pixelCentre, float depth) {
    vec2 ndc = pixelCentre / vec2(textureSize(uDepth, 0)) * 2.0 - 1.0;
    float z = uNear / depth;
    return vec3((ndc + uProjectionOffset) / uProjectionScale * z, -z);
}

// Window position (pixels) of a view-space point in front of the eye.
vec2 windowPosition(vec3 p) {
    vec2 ndc = p.xy / -p.z * uProjectionScale - uProjectionOffset;
    return (ndc * 0.5 + 0.5) * vec2(textureSize(uDepth, 0));
}

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    ivec2 size = textureSize(uDepth, 0);
    float depth = texelFetch(uDepth, pixel, 0).r;
    if (depth <= 0.0) {
        outOcclusion = vec4(1.0);
        return;
    }
    vec2 centre = vec2(pixel) + 0.5;
    vec3 p = viewPosition(centre, depth);
    vec3 n = normalize(texelFetch(uNormal, pixel, 0).xyz);
    vec3 v = normalize(-p);
    float radiusPixels = uRadius * uProjectionScale.y * 0.5 * float(size.y) / -p.z;
    if (radiusPixels < 1.5 || dot(n, v) <= 0.0) {
        outOcclusion = vec4(1.0);
        return;
    }
    radiusPixels = min(1.25 * radiusPixels, uMaxPixels);
    int pattern = (pixel.x & 3) + 4 * (pixel.y & 3);
    float rotation = (BAYER[pattern] + 0.5) / 16.0;
    float jitter = (BAYER[(pattern * 7 + 5) & 15] + 0.5) / 16.0;
    float stepPixels = radiusPixels / float(STEPS);
    // An orthonormal basis of the plane ⟂ V.
    vec3 e1 = normalize(abs(v.y) < 0.9 ? cross(v, vec3(0.0, 1.0, 0.0)) : cross(v, vec3(1.0, 0.0, 0.0)));
    vec3 e2 = cross(v, e1);
    float a = dot(n, v);
    float occluded = 0.0;
    for (int k = 0; k < DIRECTIONS; ++k) {
        float angle = 2.0 * PI * (float(k) + rotation) / float(DIRECTIONS);
        vec3 u = cos(angle) * e1 + sin(angle) * e2;
        float b = dot(n, u);
        float cosTangent = -b * inversesqrt(a * a + b * b);
        vec2 screen = windowPosition(p + u * (0.01 * -p.z)) - centre;
        if (dot(screen, screen) < 1e-12) {
            continue;
        }
        vec2 direction = normalize(screen);
        float cosHorizon = cosTangent;
        for (int s = 0; s < STEPS; ++s) {
            vec2 offset = direction * max((float(s) + jitter) * stepPixels, 1.0);
            ivec2 q = ivec2(floor(centre + offset));
            if (any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, size))) {
                break;
            }
            float sampleDepth = texelFetch(uDepth, q, 0).r;
            if (sampleDepth <= 0.0) {
                continue;  // sky: open
            }
            vec3 d = viewPosition(vec2(q) + 0.5, sampleDepth) - p;
            float length2 = dot(d, d);
            if (length2 > uRadius * uRadius || length2 < 1e-8) {
                continue;
            }
            vec3 toward = d * inversesqrt(length2);
            if (dot(toward, n) > SIN_BIAS) {
                cosHorizon = max(cosHorizon, dot(toward, v));
            }
        }
        occluded += cosHorizon - cosTangent;
    }
    outOcclusion = vec4(1.0 - uStrength * occluded / float(DIRECTIONS));
}
