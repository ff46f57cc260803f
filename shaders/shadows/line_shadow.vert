#version 450 core
// Lines (tapered capsules, seed 001 §6.4.2) into the sun's shadow map: the orthographic
// counterpart of vegetation/line.vert. The quad is the capsule's outline box in the light's
// xy plane (aligned with the line's projection), at the depth of the capsule's point
// nearest the sun; the fragment shader casts the ray along -z from there (depth_greater).
#include "../vegetation/vegetation.glsl"

struct Line {
    vec4 startRadius;  // xyz start (model, metres), w radius
    vec4 endRadius;    // xyz end, w radius
    vec4 color;        // rgb linear, w ambient occlusion
    vec4 errors;       // x error minimum, y error maximum
};
layout(std430, binding = 1) readonly buffer Lines { Line lines[]; };

layout(location = 0) in vec4 aAxisX;  // w: tolerated error (metres per texel)
layout(location = 1) in vec4 aAxisY;  // w: dither offset
layout(location = 2) in vec4 aAxisZ;
layout(location = 3) in vec4 aOrigin;
layout(location = 4) in vec4 aTint;

uniform mat4 uProjection;  // light frame -> clip, orthographic
uniform float uTexelSize;  // metres
uniform float uBand;
uniform float uMeshError;

layout(location = 0) out vec3 vFromStart;        // ray start − line start, light frame
layout(location = 1) flat out vec4 vAxisRadius;  // end − start, start radius
layout(location = 2) flat out vec4 vFadeEnd;     // fade min, fade max, end radius, dither

void main() {
    int primitive = gl_VertexID / 6;
    Line line = lines[primitive];
    vec2 fade = intervalFade(aAxisX.w, max(line.errors.x, uMeshError), line.errors.y, uBand);
    gl_Position = vec4(2.0, 2.0, 2.0, 1.0);
    if (fade.x <= fade.y) {
        return;
    }
    mat3 instance = mat3(aAxisX.xyz, aAxisY.xyz, aAxisZ.xyz);
    float scale = length(aAxisZ.xyz);
    vec3 start = instance * line.startRadius.xyz + aOrigin.xyz;
    vec3 end = instance * line.endRadius.xyz + aOrigin.xyz;
    float r0 = line.startRadius.w * scale, r1 = line.endRadius.w * scale;
    vec2 axis = end.xy - start.xy;
    vec2 along = dot(axis, axis) > 1e-12 ? normalize(axis) : vec2(1.0, 0.0);
    vec2 side = vec2(-along.y, along.x);
    float margin = uTexelSize;  // conservative rasterisation of thin lines
    float alongMin = min(-r0, dot(axis, along) - r1) - margin;
    float alongMax = max(r0, dot(axis, along) + r1) + margin;
    float sideMin = min(-r0, dot(axis, side) - r1) - margin;
    float sideMax = max(r0, dot(axis, side) + r1) + margin;
    const vec2 corners[6] = vec2[6](vec2(0, 0), vec2(1, 0), vec2(1, 1), vec2(0, 0), vec2(1, 1), vec2(0, 1));
    vec2 k = corners[gl_VertexID % 6];
    vec2 corner = start.xy + along * mix(alongMin, alongMax, k.x) + side * mix(sideMin, sideMax, k.y);
    float top = max(start.z + r0, end.z + r1);
    vFromStart = vec3(corner, top) - start;
    vAxisRadius = vec4(end - start, r0);
    vFadeEnd = vec4(fade, r1, aAxisY.w);
    gl_Position = vec4((uProjection * vec4(corner, top, 1.0)).xyz, 1.0);
}
