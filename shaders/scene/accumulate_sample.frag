#version 450 core
// Adds one sample image to the anti-aliasing accumulation (SampleAccumulator): the shaded
// sample's display colour decoded from sRGB to linear light, and its exposed radiance,
// both times the sample's weight (additive blending into RGBA32F targets).
layout(location = 0) in vec2 vUv;
layout(location = 0) out vec4 outDisplay;   // linear display colour × weight
layout(location = 1) out vec4 outRadiance;  // radiance × exposure × weight

uniform sampler2D uDisplay;   // RGBA8, sRGB-encoded (the shading pass's attachment 0)
uniform sampler2D uRadiance;  // RGBA32F (attachment 1), read only when uLinear
uniform bool uLinear;
uniform float uWeight;

vec3 srgbToLinear(vec3 c) {
    return mix(c / 12.92, pow((c + 0.055) / 1.055, vec3(2.4)), step(vec3(0.04045), c));
}

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    vec4 display = texelFetch(uDisplay, pixel, 0);
    outDisplay = vec4(srgbToLinear(display.rgb), display.a) * uWeight;
    outRadiance = uLinear ? texelFetch(uRadiance, pixel, 0) * uWeight : vec4(0.0);
}
