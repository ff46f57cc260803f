#version 450 core
// Writes the terrain's G-buffer: albedo (linear RGB) and the view-space normal, both
// blended between clipmap level i and i - 1 like the heights (trilinear across levels).

layout(location = 0) in vec4 vDetailCoordinate;
layout(location = 1) in float vBlend;
layout(location = 2) in vec4 vHeightCoordinate;
layout(location = 3) in vec3 vUp;
layout(location = 4) in float vDistance;

uniform sampler2DArray uHeight;
uniform sampler2DArray uColor;
uniform sampler2DArray uNormals;
uniform int uTextureLevel;  // the clipmap level sampled (terrain.vert)
uniform bool uHasColor;
uniform bool uOcean;
uniform mat3 uEcefToView;

layout(location = 0) out vec4 outAlbedo;  // rgb: linear albedo, a: ambient occlusion (1)
layout(location = 1) out vec4 outNormal;  // xyz: view-space normal, w: material (1 = water)

void main() {
    int coarser = max(uTextureLevel - 1, 0);
    vec3 fineNormal = texture(uNormals, vec3(vDetailCoordinate.xy, float(uTextureLevel))).xyz;
    vec3 coarseNormal = texture(uNormals, vec3(vDetailCoordinate.zw, float(coarser))).xyz;
    vec3 normal = normalize(uEcefToView * mix(fineNormal, coarseNormal, vBlend));
    vec3 albedo = vec3(0.35);
    if (uHasColor) {
        vec3 fine = texture(uColor, vec3(vDetailCoordinate.xy, float(uTextureLevel))).rgb;
        vec3 coarse = texture(uColor, vec3(vDetailCoordinate.zw, float(coarser))).rgb;
        albedo = mix(fine, coarse, vBlend);
    }
    float material = 0.0;
    if (uOcean) {
        // Water where the (bilinear, hence smooth) height is below 0 m, anti-aliased
        // over one pixel's height change.
        float height = mix(texture(uHeight, vec3(vHeightCoordinate.xy, float(uTextureLevel))).r,
                           texture(uHeight, vec3(vHeightCoordinate.zw, float(coarser))).r, vBlend);
        material = 1.0 - smoothstep(-0.5, 0.5, height / max(fwidth(height), 1e-3));
        normal = normalize(mix(normal, normalize(vUp), material));  // a calm sea surface
    }
    outAlbedo = vec4(albedo, 1.0);
    outNormal = vec4(normal, material);
}
