#version 450 core
// Writes the anti-aliasing accumulation (SampleAccumulator) back in the shading pass's
// formats: the averaged linear display colour sRGB-encoded into attachment 0, the averaged
// radiance into attachment 1 (dropped by GL when the target has none).
layout(location = 0) in vec2 vUv;
layout(location = 0) out vec4 outColor;
layout(location = 1) out vec4 outRadiance;

uniform sampler2D uDisplaySum;
uniform sampler2D uRadianceSum;
uniform bool uLinear;

vec3 linearToSrgb(vec3 c) {
    c = clamp(c, 0.0, 1.0);
    return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    vec4 display = texelFetch(uDisplaySum, pixel, 0);
    outColor = vec4(linearToSrgb(display.rgb), clamp(display.a, 0.0, 1.0));
    outRadiance = uLinear ? texelFetch(uRadianceSum, pixel, 0) : vec4(0.0, 0.0, 0.0, 1.0);
}
