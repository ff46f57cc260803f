#version 450 core
// Point-sampled plants (seed 000 ch. 3): one point sprite per sample of the instance's
// visible set (the index buffer holds the set of the view-direction cell; gl_VertexID is
// the sample index into the storage buffer). The sprite covers the sample's disc; the
// fragment shader intersects the pixel ray with the disc.
#include "vegetation.glsl"

struct Sample {
    vec4 positionRadius;  // model frame, metres
    vec4 normalColor;     // unit normal, w: packed sRGB colour (uint bits)
};
layout(std430, binding = 2) readonly buffer Samples {
    Sample samples[];
};

layout(location = 0) in vec4 aAxisX;  // w: tolerated error
layout(location = 1) in vec4 aAxisY;  // w: dither offset
layout(location = 2) in vec4 aAxisZ;
layout(location = 3) in vec4 aOrigin;
layout(location = 4) in vec4 aTint;

uniform mat4 uProjection;
uniform float uRadiusScale;  // > 1 when a prefix of the set stands for all of it
uniform float uPixelAngle;   // radians per pixel at the image centre
uniform float uMaximumPointSize;

layout(location = 0) flat out vec4 vCenterRadius;  // view space, metres
layout(location = 1) flat out vec3 vNormal;
layout(location = 2) flat out vec3 vColor;

void main() {
    Sample s = samples[gl_VertexID];
    mat3 instance = mat3(aAxisX.xyz, aAxisY.xyz, aAxisZ.xyz);
    vec3 center = instance * s.positionRadius.xyz + aOrigin.xyz;
    float distance = max(-center.z, 1e-6);
    // A disc never shrinks below ~one pixel (a sample stands for at least its pixel).
    float radius = max(s.positionRadius.w * length(aAxisX.xyz) * uRadiusScale,
                       0.7 * distance * uPixelAngle);
    vCenterRadius = vec4(center, radius);
    vNormal = normalize(instance * s.normalColor.xyz);
    uint bits = floatBitsToUint(s.normalColor.w);
    vec3 srgb = vec3(bits & 0xFFu, (bits >> 8u) & 0xFFu, (bits >> 16u) & 0xFFu) / 255.0;
    vec3 linear = mix(srgb / 12.92, pow((srgb + 0.055) / 1.055, vec3(2.4)),
                      step(vec3(0.04045), srgb));
    vColor = linear * aTint.rgb;
    gl_Position = uProjection * vec4(center, 1.0);
    // The disc's screen extent (+2 px for the perspective offset of its outline).
    gl_PointSize = min(2.0 * radius / (distance * uPixelAngle) + 2.0, uMaximumPointSize);
}
