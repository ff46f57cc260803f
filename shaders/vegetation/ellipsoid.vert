#version 450 core
// Ray-cast ellipsoids (seed 001 §6.4.1 after Sigg et al. 2006): one quad per primitive,
// six vertices, no vertex buffer — the primitive comes from the storage buffer at
// gl_VertexID / 6, the instance from per-instance attributes (LodSelector::DrawInstance).
//
// The quad is the ellipsoid's silhouette bound, placed in the plane perpendicular to the
// direction to its centre just in front of the ellipsoid: the orthographic outline
// (eigen-decomposition of the projected shape matrix M Mᵀ), which bounds the perspective
// outline on that plane. Every ray that hits the ellipsoid crosses the quad first,
// so the quad's depth bounds the ray-cast depth from the near side (conservative depth).
//
// The ray is cast in the ellipsoid's unit-sphere frame from the quad point, i.e.
// relative to the ellipsoid's centre (the numerically stable centre of §6.4.1), never
// from the far-away camera.
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
uniform float uNear;
uniform float uBand;
uniform float uMeshError;  // > 0: the mesh takes over below this error

layout(location = 0) out vec3 vLocalOrigin;     // quad point − centre, unit-sphere frame
layout(location = 1) out vec3 vLocalDirection;  // quad point (= ray direction), same frame
layout(location = 2) out vec3 vQuadView;        // quad point, view space
layout(location = 3) flat out mat3 vLocalToViewNormal;
layout(location = 6) flat out vec4 vColorAo;
layout(location = 7) flat out vec4 vFadeNoise;  // fade min, fade max, noise cells, threshold
layout(location = 8) flat out uvec2 vSeedDither;  // noise seed, dither offset bits

void main() {
    int primitive = gl_VertexID / 6;
    int corner = gl_VertexID % 6;
    Ellipsoid e = ellipsoids[primitive];
    float error = aAxisX.w;
    vec2 fade = intervalFade(error, max(e.axis2.w, uMeshError), e.color.w, uBand);
    gl_Position = vec4(2.0, 2.0, 2.0, 1.0);  // culled unless set below
    if (fade.x <= fade.y) {
        return;
    }
    mat3 instance = mat3(aAxisX.xyz, aAxisY.xyz, aAxisZ.xyz);
    vec3 center = instance * e.centerNoise.xyz + aOrigin.xyz;
    mat3 shape = instance * mat3(e.axis0.xyz, e.axis1.xyz, e.axis2.xyz);  // unit sphere → view
    mat3 toLocal = inverse(shape);
    mat3 s = shape * transpose(shape);
    float distance = length(center);
    vec3 w = center / distance;
    float extent = sqrt(max(dot(w, s * w), 0.0));
    float nearDistance = distance - extent;
    float radius = max(max(length(shape[0]), length(shape[1])), length(shape[2]));
    if (nearDistance < uNear * 1.001 || distance <= radius * 1.0001) {
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
    const vec2 corners[6] = vec2[6](vec2(-1, -1), vec2(1, -1), vec2(1, 1), vec2(-1, -1), vec2(1, 1), vec2(-1, 1));
    vec2 k = corners[corner];
    vec3 quad = w * nearDistance + axisA * k.x + axisB * k.y;
    vLocalOrigin = toLocal * (quad - center);
    vLocalDirection = toLocal * quad;
    vQuadView = quad;
    vLocalToViewNormal = transpose(toLocal);
    vColorAo = vec4(e.color.rgb * aTint.rgb, e.axis1.w);
    vFadeNoise = vec4(fade, exp2(e.centerNoise.w), e.axis0.w);
    vSeedDither = uvec2(ellipsoidNoiseSeed(e.centerNoise.xyz), floatBitsToUint(aAxisY.w));
    gl_Position = uProjection * vec4(quad, 1.0);
}
