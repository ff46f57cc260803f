#version 450 core
// Mesh fragment: base colour × texture, alpha test for leaves (alpha < cutoff is
// discarded, seed 001 §3.2), two-sided normals, screen-door fade at the interval ends.
#include "vegetation.glsl"
#include "farfield_fade.glsl"

layout(location = 0) in vec3 vNormal;
layout(location = 1) in vec2 vUv;
layout(location = 2) in vec3 vView;
layout(location = 3) flat in vec4 vTintDither;
layout(location = 4) flat in vec2 vFade;

uniform sampler2D uTexture;
uniform bool uHasTexture;
uniform vec4 uBaseColor;     // linear RGB, alpha
uniform float uAlphaCutoff;  // < 0: opaque
uniform float uAmbientOcclusion;
uniform bool uLeaves;  // leaf triangles: thinned and recoloured by the season

layout(location = 0) out vec4 outAlbedo;
layout(location = 1) out vec4 outNormal;

void main() {
    if (farFieldCanopyPixel()) {
        discard;  // the far-field canopy has this pixel (farfield_fade.glsl)
    }
    float dither = ditherValue(gl_FragCoord.xy, vTintDither.w);
    if (dither >= vFade.x || dither < vFade.y) {
        discard;
    }
    vec4 color = uBaseColor;
    if (uHasTexture) {
        color *= texture(uTexture, vUv);  // sRGB texture: decoded to linear by the sampler
    }
    if (uAlphaCutoff >= 0.0 && color.a < uAlphaCutoff) {
        discard;
    }
    if (uLeaves) {
        // A share uLeafFraction of the leaf triangles is kept, chosen per triangle and
        // instance by a hash, so neighbouring trees lose different leaves.
        uint kept = pcg3d(uvec3(uint(gl_PrimitiveID), floatBitsToUint(vTintDither.w), 0x5EA5u)).x;
        if (float(kept >> 8u) / 16777216.0 >= uLeafFraction) {
            discard;
        }
        color.rgb = seasonalLeafColour(color.rgb);
    }
    vec3 normal = normalize(vNormal);
    if (dot(normal, vView) > 0.0) {
        normal = -normal;
    }
    outAlbedo = vec4(color.rgb * vTintDither.rgb, uAmbientOcclusion);
    outNormal = vec4(normal, 2.0);  // material 2: leaves (shade.frag)
}
