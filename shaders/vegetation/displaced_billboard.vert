#version 450 core
// Displacement-mapped billboard clouds (seed 000 ch. 5): each billboard quad of the level
// drawn as its box (the quad thickened by ±halfThickness along its normal), 36 vertices
// per box (gl_VertexID / 36 is the box), instanced by LodSelector's DrawInstance
// attributes. The fragment shader ray-marches the box (displaced_billboard.frag).
#include "vegetation.glsl"

struct Box {
    vec4 originHalf;  // corner 0 (model frame, metres), w: half thickness (metres)
    vec4 edgeS;       // corner 0 → 1 (atlas +u)
    vec4 edgeT;       // corner 0 → 3 (atlas −v)
    vec4 normal;      // unit plane normal
    vec4 atlasRect;   // u0, v0 (top), u1, v1 (bottom) in the atlas
};
layout(std430, binding = 3) readonly buffer Boxes {
    Box boxes[];
};

layout(location = 0) in vec4 aAxisX;  // w: tolerated error
layout(location = 1) in vec4 aAxisY;  // w: dither offset
layout(location = 2) in vec4 aAxisZ;
layout(location = 3) in vec4 aOrigin;
layout(location = 4) in vec4 aTint;

uniform mat4 uProjection;
uniform float uBand;
uniform vec2 uInterval;  // error interval of this level

layout(location = 0) flat out vec3 vOrigin;  // view space
layout(location = 1) flat out vec3 vEdgeS;
layout(location = 2) flat out vec3 vEdgeT;
layout(location = 3) flat out vec3 vEdgeW;  // normal × half thickness
layout(location = 4) flat out vec4 vAtlasRect;
layout(location = 5) flat out vec4 vTintDither;
layout(location = 6) flat out vec2 vFade;
layout(location = 7) flat out float vHalfThickness;  // model frame, metres

// The unit box [0,1]² × [−1,1], outward faces counter-clockwise.
const vec3 kCorners[8] = vec3[8](vec3(0, 0, -1), vec3(1, 0, -1), vec3(1, 1, -1), vec3(0, 1, -1),
                                 vec3(0, 0, 1), vec3(1, 0, 1), vec3(1, 1, 1), vec3(0, 1, 1));
const int kIndices[36] = int[36](0, 2, 1, 0, 3, 2,  // w = −1 (faces −w)
                                 4, 5, 6, 4, 6, 7,  // w = +1
                                 0, 1, 5, 0, 5, 4,  // t = 0
                                 2, 3, 7, 2, 7, 6,  // t = 1
                                 1, 2, 6, 1, 6, 5,  // s = 1
                                 3, 0, 4, 3, 4, 7);  // s = 0

void main() {
    Box box = boxes[gl_VertexID / 36];
    vec3 corner = kCorners[kIndices[gl_VertexID % 36]];
    mat3 instance = mat3(aAxisX.xyz, aAxisY.xyz, aAxisZ.xyz);
    vOrigin = instance * box.originHalf.xyz + aOrigin.xyz;
    vEdgeS = instance * box.edgeS.xyz;
    vEdgeT = instance * box.edgeT.xyz;
    vEdgeW = instance * (box.normal.xyz * box.originHalf.w);
    vAtlasRect = box.atlasRect;
    vHalfThickness = box.originHalf.w;
    vTintDither = vec4(aTint.rgb, aAxisY.w);
    vFade = intervalFade(aAxisX.w, uInterval.x, uInterval.y, uBand);
    vec3 view = vOrigin + corner.x * vEdgeS + corner.y * vEdgeT + corner.z * vEdgeW;
    gl_Position = uProjection * vec4(view, 1.0);
}
