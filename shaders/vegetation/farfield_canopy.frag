#version 450 core
// The far-field canopy (FarFieldCanopy, seed 000 ch. 6): the terrain rings displaced by
// the combined elevation map (terrain + canopy height), written to the G-buffer like the
// terrain and the trees. Canopy albedo and cover come from the cover clipmap (the colour
// slot of the rings); inside the instance distance the screen-door hand-over gives the
// pixel to the trees.
//
// Looking like the forest it continues (docs/architecture.md, "Far-field canopy"):
//  - Gaps. The stored cover is the opacity of 100 m of stand seen side-on; the cover
//    along this pixel's ray is that of the crowns' Boolean model (CanopyProfile) with
//    the ray's slope: optical depth n w (pi w / 4 + h tan(zenith)), so from above the
//    ground between the crowns shows as it does between the drawn trees. The pixel is
//    kept with that probability (crown cells where they cover two pixels or more, else
//    a per-pixel dither uncorrelated with the hand-over's Bayer matrix); the rest
//    discards to the terrain drawn before. Edges of the forest are thereby dithered
//    over the bilinear cover, not texel squares.
//  - Crowns. Where a crown cell (the crown width, a power of two of the clipmap texel
//    so cells nest across levels) covers two pixels or more, each cell is a round crown
//    with a hemispherical normal and the corners between crowns are shaded understorey;
//    farther away, where the ShadingPass cannot see those normals, the albedo is scaled
//    by the mean shading of such a crown relative to the flat canopy surface (clamped
//    to darken only): the crowns' self-shadowing.
//  - Variation. Crown cells vary in brightness by ±12 %, and a world-anchored value
//    noise over the clipmap texels by ±8 % everywhere.
#include "farfield_fade.glsl"
#include "../terrain/clipmap.glsl"

layout(location = 0) in vec4 vDetailCoordinate;
layout(location = 1) in float vBlend;
layout(location = 2) in vec4 vHeightCoordinate;
layout(location = 3) in vec3 vUp;
layout(location = 4) in float vDistance;

uniform sampler2DArray uColor;    // cover layer: rgb linear albedo, a side-on cover [0, 1)
uniform sampler2DArray uNormals;  // normals of the combined elevation map (ECEF)
uniform int uTextureLevel;  // the clipmap level sampled (terrain.vert)
uniform mat3 uEcefToView;
uniform float uMinimumCover;      // below about this (side-on) the terrain is left to show
uniform float uAmbientOcclusion;  // the species' mean (G-buffer alpha, like the trees)
uniform vec3 uSunView;            // direction to the sun, view space (unit)
uniform vec3 uCrown;              // x: crown width (m), y: crown depth (m), z: sight depth (m)

layout(location = 0) out vec4 outAlbedo;
layout(location = 1) out vec4 outNormal;

const float kEarthRadius = 6371000.0;

uint hash(uvec2 v) {
    uint h = v.x * 0x8da6b343u ^ v.y * 0xd8163841u;
    h ^= h >> 15;
    h *= 0x2c1b3c6du;
    h ^= h >> 12;
    h *= 0x297a2d39u;
    h ^= h >> 15;
    return h;
}

float unitHash(uvec2 v, uint salt) {
    return float(hash(v + uvec2(salt * 0x9e37u, salt)) >> 8) / 16777216.0;
}

// Interleaved gradient noise (Jimenez 2014): a per-pixel threshold in [0, 1) with no
// structure in common with the 4×4 Bayer matrix of the hand-over.
float pixelNoise() {
    return fract(52.9829189 * fract(dot(gl_FragCoord.xy, vec2(0.06711056, 0.00583715))));
}

// Bilinear value noise over the level's texels, world-anchored (toroidal texel indices).
float texelNoise(vec2 texel) {
    vec2 p = texel - 0.5;
    uvec2 i = uvec2(mod(floor(p), uClipmapSize));
    uvec2 j = uvec2(mod(floor(p) + 1.0, uClipmapSize));
    vec2 f = fract(p);
    float a = mix(unitHash(i, 7u), unitHash(uvec2(j.x, i.y), 7u), f.x);
    float b = mix(unitHash(uvec2(i.x, j.y), 7u), unitHash(j, 7u), f.x);
    return mix(a, b, f.y);
}

// Mean of max(0, n·sun) over a hemispherical crown seen from above, relative to the
// flat canopy's max(0, normal·sun): sixteen normals of the cap (equal projected area).
float crownSelfShadowing(vec3 normal, vec3 tangent, vec3 bitangent) {
    float flatShading = max(dot(normal, uSunView), 0.0);
    if (flatShading <= 1e-3) {
        return 1.0;
    }
    float sum = 0.0;
    for (int k = 0; k < 16; ++k) {
        float r = sqrt((float(k >> 2) + 0.5) / 4.0);
        float a = (float(k & 3) + 0.5 + 0.5 * float(k >> 2)) * 1.5707963;
        vec2 d = r * vec2(cos(a), sin(a));
        vec3 n = d.x * tangent + d.y * bitangent + sqrt(max(1.0 - dot(d, d), 0.0)) * normal;
        sum += max(dot(n, uSunView), 0.0);
    }
    return min(sum / 16.0 / flatShading, 1.0);
}

void main() {
    // The hand-over first: it needs no texture, and inside the band it gives most pixels
    // to the trees (nearer than the fade start the geometry is clipped, see terrain.vert).
    if (!farFieldCanopyPixel()) {
        discard;
    }
    int coarser = max(uTextureLevel - 1, 0);
    vec4 fine = texture(uColor, vec3(vDetailCoordinate.xy, float(uTextureLevel)));
    vec4 coarse = texture(uColor, vec3(vDetailCoordinate.zw, float(coarser)));
    vec4 cover = mix(fine, coarse, vBlend);
    // The minimum cover is a dithered threshold (mean uMinimumCover), so the forest's
    // thin edge fades out instead of ending on a contour.
    if (cover.a < uMinimumCover * 2.0 * pixelNoise()) {
        discard;
    }
    vec3 fineNormal = texture(uNormals, vec3(vDetailCoordinate.xy, float(uTextureLevel))).xyz;
    vec3 coarseNormal = texture(uNormals, vec3(vDetailCoordinate.zw, float(coarser))).xyz;
    vec3 normal = normalize(uEcefToView * mix(fineNormal, coarseNormal, vBlend));

    // The fragment's view-space position (as the fade computes its distance).
    float viewDepth = uFarFieldFade.z / max(gl_FragCoord.z, 1e-30);
    vec3 position = vec3((gl_FragCoord.xy * uFarFieldRay.xy + uFarFieldRay.zw) * viewDepth,
                         -viewDepth);
    vec3 toEye = normalize(-position);

    // Cover along this ray: the side-on cover gives n w per metre of path.
    float lineDensity = -log(max(1.0 - cover.a, 1e-6)) / uCrown.z;
    float cosZenith = clamp(dot(toEye, normal), 0.02, 1.0);
    float tanZenith = sqrt(1.0 - cosZenith * cosZenith) / cosZenith;
    float seen = 1.0 - exp(-lineDensity * (0.785398 * uCrown.x + uCrown.y * tanZenith));

    // Crown cells: the crown width rounded to the level's texel by a power of two.
    vec2 texel = vDetailCoordinate.xy * uClipmapSize;
    float texelMetres = kEarthRadius / uDetailLevels[uTextureLevel].y;
    float cellsPerTexel = exp2(round(log2(max(texelMetres / uCrown.x, 1.0))));
    vec2 cellCoordinate = texel * cellsPerTexel;
    uvec2 cell = uvec2(mod(floor(cellCoordinate), uClipmapSize * cellsPerTexel));

    // Tangents of the cell coordinates (Schüler's cotangent frame from derivatives).
    vec3 dp1 = dFdx(position), dp2 = dFdy(position);
    vec2 duv1 = dFdx(cellCoordinate), duv2 = dFdy(cellCoordinate);
    // Pixels a cell spans in its most foreshortened direction (grazing slopes compress
    // cells that are large by distance alone).
    float cellPixels = 1.0 / max(max(length(duv1), length(duv2)), 1e-6);
    vec3 tangent = cross(dp2, normal) * duv1.x + cross(normal, dp1) * duv2.x;
    tangent = normalize(tangent - normal * dot(normal, tangent) + 1e-12);
    vec3 bitangent = -cross(normal, tangent);  // v runs south in the clipmap

    float brightness = 1.0 + 0.16 * (texelNoise(texel) - 0.5);
    vec3 shaded = normal;
    float occlusion = uAmbientOcclusion;
    bool crowns = cellPixels >= 2.0;
    if (crowns) {
        if (unitHash(cell, 1u) >= seen) {
            discard;  // a gap between crowns: the terrain shows
        }
        vec2 local = 2.0 * (fract(cellCoordinate) - 0.5);  // [-1, 1] across the cell
        float r2 = dot(local, local);
        brightness *= 0.88 + 0.24 * unitHash(cell, 2u);
        if (r2 < 1.0) {
            shaded = normalize(local.x * tangent + local.y * bitangent + sqrt(1.0 - r2) * normal);
        } else {
            occlusion *= 0.6;  // between the crowns, lower in the canopy
        }
    } else {
        if (pixelNoise() >= seen) {
            discard;
        }
        brightness *= crownSelfShadowing(normal, tangent, bitangent);
    }
    outAlbedo = vec4(cover.rgb * brightness, occlusion);
    outNormal = vec4(shaded, 2.0);  // material 2: leaves (shade.frag)
}
