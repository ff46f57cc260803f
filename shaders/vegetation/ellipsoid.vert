#version 450 core
// Ray-cast ellipsoids (seed 001 §6.4.1 after Sigg et al. 2006): one point sprite per
// primitive, as in Sigg et al. — a single vertex invocation and a single rasterised
// primitive each (six vertices and two triangles per quad cost 3–4× more on llvmpipe,
// whose vertex processing and triangle setup run on one thread; docs/benchmarks.md).
// The primitive comes from the storage buffer at gl_VertexID, the instance from the
// per-instance attributes (LodSelector::DrawInstance).
//
// Screen bound: the ellipsoid's orthographic outline in the plane perpendicular to the
// direction to its centre, just in front of the ellipsoid (eigen-decomposition of the
// projected shape matrix M Mᵀ), bounds the perspective outline on that plane; the screen
// box of that quad bounds the ellipsoid on screen. (Sigg et al. solve the projected
// quadric for the box directly; in float that cancels catastrophically for a 0.3 m
// ellipsoid kilometres away, the quad does not.) Sprites larger than the largest point
// size the driver rasterises are drawn in a second pass (uQuadPass) as the quad itself,
// six vertices; each primitive is drawn by exactly one of the two passes.
//
// Depth: the sprite's depth is the ellipsoid's nearest view depth, so the ray-cast depth
// is never nearer (conservative depth, depth_less in the fragment shader).
//
// The fragment shader casts the pixel's ray in the ellipsoid's unit-sphere frame from
// the ray's crossing with that plane, i.e. relative to the ellipsoid's centre (the
// numerically stable centre of §6.4.1), never from the far-away camera.
#include "vegetation.glsl"

struct Ellipsoid {
    vec4 centerNoise;  // xyz centre (model, metres), w noise level
    vec4 axis0;        // xyz axis × radius, w alpha threshold
    vec4 axis1;        // xyz axis × radius, w ambient occlusion
    vec4 axis2;        // xyz axis × radius, w error minimum
    vec4 color;        // rgb linear, w error maximum
};
layout(std430, binding = 0) readonly buffer Ellipsoids { Ellipsoid ellipsoids[]; };

layout(location = 0) in vec4 aAxisX;   // w: tolerated error (metres per pixel)
layout(location = 1) in vec4 aAxisY;   // w: dither offset
layout(location = 2) in vec4 aAxisZ;
layout(location = 3) in vec4 aOrigin;
layout(location = 4) in vec4 aTint;

uniform mat4 uProjection;
uniform vec2 uViewport;        // pixels
uniform float uNear;
uniform float uBand;
uniform float uMeshError;      // > 0: the mesh takes over below this error
uniform float uMaximumPointSize;  // pixels: larger sprites go to the quad pass
uniform bool uQuadPass;        // false: GL_POINTS, one vertex per primitive; true: quads

layout(location = 0) flat out mat3 vToLocal;          // view → unit-sphere frame
layout(location = 3) flat out vec3 vLocalCenter;      // toLocal × centre
layout(location = 4) flat out vec4 vPlane;            // xyz: unit direction to the centre, w: plane distance
layout(location = 5) flat out vec4 vColorAo;
layout(location = 6) flat out vec4 vFadeNoise;        // fade min, fade max, noise cells, threshold
layout(location = 7) flat out uvec2 vSeedDither;      // noise seed, dither offset bits

void main() {
    int primitive = uQuadPass ? gl_VertexID / 6 : gl_VertexID;
    Ellipsoid e = ellipsoids[primitive];
    float error = aAxisX.w;
    vec2 fade = intervalFade(error, max(e.axis2.w, uMeshError), e.color.w, uBand);
    gl_Position = vec4(2.0, 2.0, 2.0, 1.0);  // culled unless set below
    gl_PointSize = 1.0;
    if (fade.x <= fade.y || uLeafFraction <= 0.0) {
        return;  // faded out, or no leaves (leaf-off)
    }
    mat3 instance = mat3(aAxisX.xyz, aAxisY.xyz, aAxisZ.xyz);
    vec3 center = instance * e.centerNoise.xyz + aOrigin.xyz;
    mat3 shape = instance * mat3(e.axis0.xyz, e.axis1.xyz, e.axis2.xyz);  // unit sphere → view
    mat3 s = shape * transpose(shape);
    float distance = length(center);
    vec3 w = center / distance;
    float extent = sqrt(max(dot(w, s * w), 0.0));
    float nearDistance = distance - extent;
    float radius = max(max(length(shape[0]), length(shape[1])), length(shape[2]));
    float nearestDepth = -center.z - sqrt(max(s[2][2], 0.0));
    if (nearDistance < uNear * 1.001 || distance <= radius * 1.0001 || nearestDepth < uNear) {
        return;  // reaches the near plane: close-ups draw the mesh
    }
    vec3 e1 = normalize(abs(w.x) < 0.9 ? cross(w, vec3(1.0, 0.0, 0.0)) : cross(w, vec3(0.0, 1.0, 0.0)));
    vec3 e2 = cross(w, e1);
    vec3 s1 = s * e1, s2 = s * e2;
    float a = dot(e1, s1), b = dot(e1, s2), c = dot(e2, s2);
    float mean = 0.5 * (a + c), root = sqrt(max(0.25 * (a - c) * (a - c) + b * b, 0.0));
    float l1 = mean + root, l2 = max(mean - root, 0.0);
    vec2 v1 = abs(b) > 1e-12 * (a + c) ? normalize(vec2(l1 - c, b)) : (a >= c ? vec2(1.0, 0.0) : vec2(0.0, 1.0));
    vec2 v2 = vec2(-v1.y, v1.x);
    // A point c + u of the ellipsoid meets the plane at lateral offset
    // u⊥ · nearDistance / (distance + u·w), and distance + u·w >= nearDistance: the
    // orthographic outline itself bounds the perspective one on this plane.
    const float scale = 1.01;
    vec3 axisA = (e1 * v1.x + e2 * v1.y) * sqrt(l1) * scale;
    vec3 axisB = (e1 * v2.x + e2 * v2.y) * sqrt(l2) * scale;
    vec3 middle = w * nearDistance;
    // Screen box of the quad. A quad reaching behind the camera has no box: the quad
    // pass draws it, clipped by the rasteriser.
    vec2 low = vec2(1e30), high = vec2(-1e30);
    vec4 clip[4];
    bool behind = false;
    for (int i = 0; i < 4; ++i) {
        vec2 k = vec2((i & 1) != 0 ? 1.0 : -1.0, (i & 2) != 0 ? 1.0 : -1.0);
        clip[i] = uProjection * vec4(middle + axisA * k.x + axisB * k.y, 1.0);
        behind = behind || clip[i].w <= uNear;
        vec2 ndc = clip[i].xy / max(clip[i].w, uNear);
        low = min(low, ndc);
        high = max(high, ndc);
    }
    vec2 pixels = (high - low) * 0.5 * uViewport;
    float size = behind ? 1e30 : max(pixels.x, pixels.y) + 2.0;  // whole pixels on either side
    float depth = uNear / nearestDepth;  // reversed-Z NDC of the nearest point
    if (uQuadPass) {
        if (size <= uMaximumPointSize) {
            return;
        }
        const int corners[6] = int[6](0, 1, 3, 0, 3, 2);
        vec4 corner = clip[corners[gl_VertexID % 6]];
        gl_Position = vec4(corner.xy, depth * corner.w, corner.w);
    } else {
        if (size > uMaximumPointSize) {
            return;
        }
        gl_Position = vec4(0.5 * (low + high), depth, 1.0);
        gl_PointSize = size;
    }
    mat3 toLocal = inverse(shape);
    vToLocal = toLocal;
    vLocalCenter = toLocal * center;
    vPlane = vec4(w, nearDistance);
    vColorAo = vec4(seasonalLeafColour(e.color.rgb) * aTint.rgb, e.axis1.w);
    vFadeNoise = vec4(fade, exp2(e.centerNoise.w), seasonalThreshold(e.axis0.w));
    vSeedDither = uvec2(ellipsoidNoiseSeed(e.centerNoise.xyz), floatBitsToUint(aAxisY.w));
}
