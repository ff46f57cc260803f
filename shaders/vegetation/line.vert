#version 450 core
// Ray-cast lines (seed 001 §6.4.2, the triangle-based method of Merhof et al. 2006):
// each line is a tapered capsule; one screen-aligned quad per line bounds its silhouette
// (the perspective projections of both end spheres onto a plane in front of the line).
// The fragment shader intersects the ray with the capsule, relative to the line's start.
#include "vegetation.glsl"

struct Line {
    vec4 startRadius;  // xyz start (model, metres), w radius
    vec4 endRadius;    // xyz end, w radius
    vec4 color;        // rgb linear, w ambient occlusion
    vec4 errors;       // x error minimum, y error maximum
};
layout(std430, binding = 1) readonly buffer Lines { Line lines[]; };

layout(location = 0) in vec4 aAxisX;  // w: tolerated error (metres per pixel)
layout(location = 1) in vec4 aAxisY;  // w: dither offset
layout(location = 2) in vec4 aAxisZ;
layout(location = 3) in vec4 aOrigin;
layout(location = 4) in vec4 aTint;

uniform mat4 uProjection;
uniform float uNear;
uniform float uBand;
uniform float uMeshError;

layout(location = 0) out vec3 vFromStart;  // quad point − line start, view space
layout(location = 1) out vec3 vDirection;  // quad point (= ray direction), view space
layout(location = 2) flat out vec4 vAxisRadius;  // end − start, start radius
layout(location = 3) flat out vec4 vColorAo;
layout(location = 4) flat out vec4 vFadeEnd;  // fade min, fade max, end radius, dither

void main() {
    int primitive = gl_VertexID / 6;
    int corner = gl_VertexID % 6;
    Line line = lines[primitive];
    float error = aAxisX.w;
    vec2 fade = intervalFade(error, max(line.errors.x, uMeshError), line.errors.y, uBand);
    gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
    if (fade.x <= fade.y) {
        return;
    }
    mat3 instance = mat3(aAxisX.xyz, aAxisY.xyz, aAxisZ.xyz);
    float scale = length(aAxisZ.xyz);
    vec3 start = instance * line.startRadius.xyz + aOrigin.xyz;
    vec3 end = instance * line.endRadius.xyz + aOrigin.xyz;
    float r0 = line.startRadius.w * scale, r1 = line.endRadius.w * scale;
    float rMax = max(r0, r1);
    vec3 middle = 0.5 * (start + end);
    vec3 v = normalize(middle);
    // The plane perpendicular to v just in front of the capsule.
    float planeDistance = min(dot(start, v) - r0, dot(end, v) - r1);
    if (planeDistance < uNear * 1.001) {
        return;
    }
    vec3 axis = end - start;
    vec3 side = cross(axis, v);
    side = dot(side, side) > 1e-12 * dot(axis, axis) ? normalize(side)
                                                      : normalize(abs(v.x) < 0.9 ? cross(v, vec3(1, 0, 0)) : cross(v, vec3(0, 1, 0)));
    vec3 along = cross(v, side);
    // End points projected onto the plane, and bounds of their spheres' images there
    // (no point of a sphere is nearer than d − r).
    float ds = dot(start, v), de = dot(end, v);
    vec3 ps = start * (planeDistance / ds), pe = end * (planeDistance / de);
    float rs = r0 * planeDistance / max(ds - r0, 1e-6) * 1.02;
    float re = r1 * planeDistance / max(de - r1, 1e-6) * 1.02;
    vec3 center = v * planeDistance;
    float as = dot(ps - center, along), ae = dot(pe - center, along);
    float ss = dot(ps - center, side), se = dot(pe - center, side);
    float alongMin = min(as - rs, ae - re), alongMax = max(as + rs, ae + re);
    float sideMin = min(ss - rs, se - re), sideMax = max(ss + rs, se + re);
    const vec2 corners[6] = vec2[6](vec2(0, 0), vec2(1, 0), vec2(1, 1), vec2(0, 0), vec2(1, 1), vec2(0, 1));
    vec2 k = corners[corner];
    vec3 quad = center + along * mix(alongMin, alongMax, k.x) + side * mix(sideMin, sideMax, k.y);
    vFromStart = quad - start;
    vDirection = quad;
    vAxisRadius = vec4(axis, r0);
    vColorAo = vec4(line.color.rgb * aTint.rgb, line.color.w);
    vFadeEnd = vec4(fade, r1, aAxisY.w);
    gl_Position = uProjection * vec4(quad, 1.0);
}
