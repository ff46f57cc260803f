#version 450 core
// The far-field canopy (FarFieldCanopy, seed 000 ch. 6): the terrain rings displaced by
// the combined elevation map (terrain + canopy height), written to the G-buffer like the
// terrain and the trees. Canopy albedo and cover come from the cover clipmap (the colour
// slot of the rings); where there is no forest the fragment is discarded so the terrain
// drawn before shows, and inside the instance distance the screen-door hand-over gives
// the pixel to the trees.
#include "farfield_fade.glsl"

layout(location = 0) in vec4 vDetailCoordinate;
layout(location = 1) in float vBlend;
layout(location = 2) in vec4 vHeightCoordinate;
layout(location = 3) in vec3 vUp;
layout(location = 4) in float vDistance;

uniform sampler2DArray uColor;    // cover layer: rgb linear albedo, a cover [0, 1]
uniform sampler2DArray uNormals;  // normals of the combined elevation map (ECEF)
uniform int uTextureLevel;  // the clipmap level sampled (terrain.vert)
uniform mat3 uEcefToView;
uniform float uMinimumCover;      // below this the canopy is left to the terrain
uniform float uAmbientOcclusion;  // the species' mean (G-buffer alpha, like the trees)

layout(location = 0) out vec4 outAlbedo;
layout(location = 1) out vec4 outNormal;

void main() {
    int coarser = max(uTextureLevel - 1, 0);
    vec4 fine = texture(uColor, vec3(vDetailCoordinate.xy, float(uTextureLevel)));
    vec4 coarse = texture(uColor, vec3(vDetailCoordinate.zw, float(coarser)));
    vec4 cover = mix(fine, coarse, vBlend);
    if (cover.a < uMinimumCover || !farFieldCanopyPixel()) {
        discard;
    }
    vec3 fineNormal = texture(uNormals, vec3(vDetailCoordinate.xy, float(uTextureLevel))).xyz;
    vec3 coarseNormal = texture(uNormals, vec3(vDetailCoordinate.zw, float(coarser))).xyz;
    vec3 normal = normalize(uEcefToView * mix(fineNormal, coarseNormal, vBlend));
    outAlbedo = vec4(cover.rgb, uAmbientOcclusion);
    outNormal = vec4(normal, 2.0);  // material 2: leaves (shade.frag)
}
