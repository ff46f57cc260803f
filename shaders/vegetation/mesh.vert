#version 450 core
// The source mesh (close-ups and the reference) and billboard-cloud levels: instanced
// triangles, the instance transform from LodSelector::DrawInstance attributes.
#include "vegetation.glsl"

layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in vec2 aUv;
layout(location = 3) in vec4 aAxisX;  // w: tolerated error
layout(location = 4) in vec4 aAxisY;  // w: dither offset
layout(location = 5) in vec4 aAxisZ;
layout(location = 6) in vec4 aOrigin;
layout(location = 7) in vec4 aTint;

uniform mat4 uProjection;
uniform float uBand;
uniform vec2 uInterval;  // error interval in which this mesh is drawn

layout(location = 0) out vec3 vNormal;
layout(location = 1) out vec2 vUv;
layout(location = 2) out vec3 vView;
layout(location = 3) flat out vec4 vTintDither;
layout(location = 4) flat out vec2 vFade;

void main() {
    mat3 instance = mat3(aAxisX.xyz, aAxisY.xyz, aAxisZ.xyz);
    vec3 view = instance * aPosition + aOrigin.xyz;
    vNormal = normalize(instance * aNormal);  // uniform scale: no inverse transpose needed
    vUv = aUv;
    vView = view;
    vTintDither = vec4(aTint.rgb, aAxisY.w);
    vFade = intervalFade(aAxisX.w, uInterval.x, uInterval.y, uBand);
    gl_Position = uProjection * vec4(view, 1.0);
}
