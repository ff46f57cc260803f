#version 450 core
// DMBBC fragment (seed 000 ch. 5.2): the back faces of each box are rasterized (front
// faces culled, so a camera inside a box still sees it); the pixel ray is clipped to the
// box (slabs in the box frame: s, t ∈ [0, 1] across the quad, w ∈ [−1, 1] through its
// thickness) and marched one atlas texel per step from where it enters. A step hits when
// the texel is opaque in the level's atlas and the ray's w over the step overlaps the
// texel's thick-shell interval (lowest, highest height of the geometry projected there);
// the hit's depth is written (reversed-Z: near / distance along −z). The hit is never
// behind the rasterized back face, hence depth_greater (seed 000 ch. 9: "push up").
#include "vegetation.glsl"

layout(location = 0) flat in vec3 vOrigin;
layout(location = 1) flat in vec3 vEdgeS;
layout(location = 2) flat in vec3 vEdgeT;
layout(location = 3) flat in vec3 vEdgeW;
layout(location = 4) flat in vec4 vAtlasRect;
layout(location = 5) flat in vec4 vTintDither;
layout(location = 6) flat in vec2 vFade;
layout(location = 7) flat in float vHalfThickness;

uniform mat4 uProjection;
uniform vec2 uViewport;  // pixels
uniform float uNear;
uniform sampler2D uAtlas;    // sRGB colour, binary alpha, mipmapped
uniform sampler2D uHeights;  // RG: lowest, highest height (metres), nearest
uniform float uAlphaCutoff;
uniform int uMaximumSteps;

layout(location = 0) out vec4 outAlbedo;
layout(location = 1) out vec4 outNormal;
layout(depth_greater) out float gl_FragDepth;

void main() {
    vec2 ndc = gl_FragCoord.xy / uViewport * 2.0 - 1.0;
    vec3 ray = vec3((ndc.x + uProjection[2][0]) / uProjection[0][0],
                    (ndc.y + uProjection[2][1]) / uProjection[1][1], -1.0);
    // Box coordinates along the ray: c(λ) = λ·a − b per axis (the edges are orthogonal).
    vec3 lengths2 = vec3(dot(vEdgeS, vEdgeS), dot(vEdgeT, vEdgeT), dot(vEdgeW, vEdgeW));
    vec3 a = vec3(dot(ray, vEdgeS), dot(ray, vEdgeT), dot(ray, vEdgeW)) / lengths2;
    vec3 b = vec3(dot(vOrigin, vEdgeS), dot(vOrigin, vEdgeT), dot(vOrigin, vEdgeW)) / lengths2;
    vec3 low = vec3(0.0, 0.0, -1.0), high = vec3(1.0);
    vec3 safeA = mix(vec3(1e-12), a, greaterThan(abs(a), vec3(1e-12)));
    vec3 t0 = (low + b) / safeA, t1 = (high + b) / safeA;
    vec3 tNear = min(t0, t1), tFar = max(t0, t1);
    float enter = max(max(tNear.x, tNear.y), max(tNear.z, uNear));
    float leave = min(min(tFar.x, tFar.y), tFar.z);
    // Level of detail of the atlas from the entry point's footprint (before any discard).
    vec2 atlasSize = vec2(textureSize(uAtlas, 0));
    vec2 entry = enter * a.xy - b.xy;
    vec2 entryUv = mix(vAtlasRect.xy, vAtlasRect.zw, vec2(entry.x, 1.0 - entry.y));
    vec2 footprint = fwidth(entryUv) * atlasSize;
    float lod = log2(max(max(footprint.x, footprint.y), 1.0));
    float dither = ditherValue(gl_FragCoord.xy, vTintDither.w);
    if (leave <= enter || dither >= vFade.x || dither < vFade.y) {
        discard;
    }
    // One step per texel crossed (at least one), at most uMaximumSteps.
    vec2 tileTexels = abs(vAtlasRect.zw - vAtlasRect.xy) * atlasSize;
    vec2 across = abs(a.xy) * (leave - enter) * tileTexels;
    int steps = clamp(int(ceil(max(across.x, across.y))) + 1, 1, uMaximumSteps);
    float step = (leave - enter) / float(steps);
    ivec2 heightSize = textureSize(uHeights, 0);
    for (int i = 0; i < steps; ++i) {
        float lambdaA = enter + float(i) * step;
        vec3 ca = lambdaA * a - b;
        vec3 cb = (lambdaA + step) * a - b;
        vec2 st = clamp(0.5 * (ca.xy + cb.xy), 0.0, 1.0);
        vec2 uv = mix(vAtlasRect.xy, vAtlasRect.zw, vec2(st.x, 1.0 - st.y));
        vec4 color = textureLod(uAtlas, uv, lod);
        if (color.a < uAlphaCutoff) {
            continue;
        }
        ivec2 texel = clamp(ivec2(uv * vec2(heightSize)), ivec2(0), heightSize - 1);
        // The texel's heights in box units (w = height / half thickness).
        vec2 shell = texelFetch(uHeights, texel, 0).rg / vHalfThickness;
        float wa = ca.z, wb = cb.z;
        if (max(wa, wb) < shell.x || min(wa, wb) > shell.y) {
            continue;
        }
        // Where the ray enters the interval within the step.
        float target = clamp(wa, shell.x, shell.y);
        float f = abs(wb - wa) > 1e-9 ? clamp((target - wa) / (wb - wa), 0.0, 1.0) : 0.0;
        vec3 hit = ray * (lambdaA + f * step);
        gl_FragDepth = max(uNear / max(-hit.z, uNear), gl_FragCoord.z);
        vec3 normal = normalize(vEdgeW);
        if (dot(normal, hit) > 0.0) {
            normal = -normal;
        }
        outAlbedo = vec4(color.rgb * vTintDither.rgb, 1.0);
        outNormal = vec4(normal, 2.0);  // material 2: leaves (shade.frag)
        return;
    }
    discard;
}
