#version 450 core
// The far-field canopy (FarFieldCanopy, seed 000 ch. 6): the terrain rings displaced by
// the combined elevation map (terrain + canopy height), written to the G-buffer like the
// terrain and the trees. Canopy albedo and cover come from the cover clipmap (the colour
// slot of the rings); inside the instance distance the screen-door hand-over gives the
// pixel to the trees.
//
// Looking like the trees it continues (docs/architecture.md, "Far-field canopy"): what the
// drawn trees show at the hand-over on the render date is the crowns of their coarsest
// LoD level in the species' leaf states (CanopyProfile::crowns, CrownSilhouette), given
// here as opaque projected areas per instance (uCrown.y from above, uCrown.z from the
// side) and a tone (uTone: their colour over the stored full-leaf albedo).
//  - Gaps. The stored cover is the opacity of 100 m of stand seen side-on, i.e. n w per
//    metre; the cover along this pixel's ray is the Boolean model's with partly
//    transparent crowns, 1 − exp(−n (A_top + A_side tan(zenith))) (A the opaque areas:
//    leaf-off crowns have none, so a winter view shows the terrain). The rest discards to
//    the terrain drawn before; forest edges dither over the bilinear cover.
//  - Crowns. Where a crown cell (a power of two of the clipmap texel near the crown width,
//    so cells nest across levels) spans two pixels or more, a cell holds one crown (a
//    disc of the crown's width, anywhere in the cell, reaching into its neighbours) that
//    is present, and within it opaque, in the proportions that give the same cover;
//    farther away each pixel is kept by a per-pixel dither. Either way a kept pixel is a
//    point on a crown facing the viewer (uniform over the crown's projected disc, as the
//    ray-cast ellipsoids' hits), so the shading pass shades the far field as it shades
//    the drawn trees. No analytic self-shadowing: it darkened the far field against the
//    trees at the hand-over.
//  - Variation. Crown cells vary in brightness by ±12 %, and a world-anchored value
//    noise over the clipmap texels by ±8 % everywhere (both mean 1).
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
uniform vec3 uTone;               // the crowns' colour on the date over the stored albedo
// x: crown width (m), y: opaque area from above (m²), z: opaque area from the side (m²),
// w: the stored cover's sight depth (m)
uniform vec4 uCrown;
uniform float uCrownOpacity;  // opaque share of a crown's outline seen from the side

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

// A per-pixel threshold in [0, 1): white noise (a hash of the pixel), with no structure
// in common with the 4×4 Bayer matrix of the hand-over. Interleaved gradient noise
// (Jimenez 2014), used first, is a lattice: kept at a thin cover (a forest seen from
// above, 10–20 %) its pixels lined up in rows of dots, visible from the demo's aircraft.
float pixelNoise() {
    return unitHash(uvec2(gl_FragCoord.xy), 9u);
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

// A point of a crown facing the viewer at disc position d (|d| <= 1) in the frame
// (right, down) across the unit direction to the eye.
vec3 crownNormal(vec2 d, vec3 right, vec3 down, vec3 toEye) {
    d /= max(length(d), 1.0);
    return normalize(d.x * right + d.y * down + sqrt(max(1.0 - dot(d, d), 0.0)) * toEye);
}

// A point of a crown's disc (x across, y down, |d| <= 1) that a line of sight reaches
// through the stand, from two uniform values. Nearer crowns hide a crown's lower part: a
// point whose disc area above it is a share u of the disc is seen with probability
// exp(−S u) (S = n A_side tan(zenith): the expected opaque crowns between it and the
// eye, per unit of that share), so u is exponential truncated to [0, 1]; u = share above
// height z (acos z − z √(1 − z²)) / π is inverted by Newton steps. At the drawn stand's
// grazing views the visible crown points are its sunlit, sky-lit tops, as here.
vec2 visibleCrownPoint(float a, float b, float S) {
    float u = S > 1e-3 ? -log(1.0 - a * (1.0 - exp(-S))) / S : a;
    float z = 1.0 - 2.0 * u;
    for (int k = 0; k < 4; ++k) {
        float c = sqrt(max(1.0 - z * z, 1e-4));
        float f = (acos(clamp(z, -1.0, 1.0)) - z * c) / 3.14159265 - u;
        z = clamp(z + f * 3.14159265 / (2.0 * c), -1.0, 1.0);
    }
    return vec2(sqrt(max(1.0 - z * z, 0.0)) * (2.0 * b - 1.0), -z);
}

// A uniform point of the unit disc from two uniform values.
vec2 discPoint(float a, float b) {
    float angle = 6.2831853 * b;
    return sqrt(a) * vec2(cos(angle), sin(angle));
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
    float lineDensity = -log(max(1.0 - cover.a, 1e-6)) / uCrown.w;
    float stems = lineDensity / max(uCrown.x, 1e-3);  // per m²
    float cosZenith = clamp(dot(toEye, normal), 0.02, 1.0);
    float tanZenith = sqrt(1.0 - cosZenith * cosZenith) / cosZenith;
    float seen = 1.0 - exp(-stems * (uCrown.y + uCrown.z * tanZenith));

    // Crown cells: the crown width rounded to the level's texel by a power of two.
    vec2 texel = vDetailCoordinate.xy * uClipmapSize;
    float texelMetres = kEarthRadius / uDetailLevels[uTextureLevel].y;
    float cellsPerTexel = exp2(round(log2(max(texelMetres / uCrown.x, 1.0))));
    vec2 cellCoordinate = texel * cellsPerTexel;

    // Tangents of the cell coordinates (Schüler's cotangent frame from derivatives).
    vec3 dp1 = dFdx(position), dp2 = dFdy(position);
    vec2 duv1 = dFdx(cellCoordinate), duv2 = dFdy(cellCoordinate);
    // Pixels a cell spans in its most foreshortened direction (grazing slopes compress
    // cells that are large by distance alone).
    float cellPixels = 1.0 / max(max(length(duv1), length(duv2)), 1e-6);
    vec3 tangent = cross(dp2, normal) * duv1.x + cross(normal, dp1) * duv2.x;
    tangent = normalize(tangent - normal * dot(normal, tangent) + 1e-12);
    vec3 bitangent = -cross(normal, tangent);  // v runs south in the clipmap
    // The cell's axes across the line of sight (foreshortening removed): a crown point's
    // disc position maps to a normal facing the viewer with the crown's own orientation
    // (its sunward side where the sun is).
    vec3 right = tangent - toEye * dot(toEye, tangent);
    right = length(right) > 1e-4 ? normalize(right) : normalize(cross(toEye, normal) + 1e-12);
    vec3 down = bitangent - toEye * dot(toEye, bitangent);
    down = length(down) > 1e-4 ? normalize(down) : cross(right, toEye);

    float brightness = 1.0 + 0.16 * (texelNoise(texel) - 0.5);
    vec2 disc;
    if (cellPixels >= 2.0) {
        // Crowns of the crown's width, one per cell at a uniform place in it (a crown may
        // reach into the neighbouring cells: a disc of radius <= half a cell around this
        // point meets at most the 2 × 2 cells nearest it, so those hold every crown that
        // can cover it). Crowns centred on their cells, as first built, lined up in the
        // clipmap's lattice: a forest seen from an aircraft was a grid of dots.
        float cellMetres = texelMetres / cellsPerTexel;
        float radius = min(0.5 * uCrown.x / cellMetres, 0.5);  // cell units
        float inDisc = 3.14159265 * radius * radius;             // one crown's share of a cell
        // Cover of a point = 1 − Π (1 − present × inside × a_i) over the four cells, a_i the
        // shares of the point's disc of possible centres in each (Σ a_i = inDisc), taken as
        // equal: present crowns with opaque points in the proportions the drawn crowns show
        // from the side; where even present crowns fully opaque fall short, per-pixel dither
        // fills the ground between them.
        float opaque = clamp(uCrownOpacity, 0.05, 1.0);
        float share = 0.25 * inDisc;
        float needed = 1.0 - pow(1.0 - min(seen, 0.9999), 0.25);  // = present × inside × share
        float present = min(needed / (share * opaque), 1.0);
        float inside = present < 1.0 ? opaque : min(needed / share, 1.0);
        float discCover = 1.0 - pow(1.0 - inside * share, 4.0);
        float between = clamp((seen - discCover) / max(1.0 - discCover, 1e-3), 0.0, 1.0);
        int crowns = 0;
        float nearest = 2.0;
        uvec2 nearestCell = uvec2(0u);
        vec2 nearestLocal = vec2(0.0);
        vec2 first = floor(cellCoordinate - 0.5);
        float wrap = uClipmapSize * cellsPerTexel;
        for (int k = 0; k < 4; ++k) {
            vec2 at = first + vec2(k & 1, k >> 1);
            uvec2 c = uvec2(mod(at, wrap));
            if (unitHash(c, 1u) >= present) {
                continue;
            }
            vec2 centre = at + vec2(unitHash(c, 3u), unitHash(c, 4u));
            vec2 local = (cellCoordinate - centre) / radius;  // the disc: |local| <= 1
            float r2 = dot(local, local);
            if (r2 < 1.0) {
                ++crowns;
                if (r2 < nearest) {
                    nearest = r2;
                    nearestCell = c;
                    nearestLocal = local;
                }
            }
        }
        float keep = crowns > 0 ? 1.0 - pow(1.0 - inside, float(crowns)) : between;
        if (pixelNoise() >= keep) {
            discard;  // a gap between or in the crowns: the terrain shows
        }
        if (crowns > 0) {
            brightness *= 0.88 + 0.24 * unitHash(nearestCell, 2u);
            disc = nearestLocal;
        } else {
            disc = discPoint(unitHash(uvec2(gl_FragCoord.xy), 5u),
                             unitHash(uvec2(gl_FragCoord.xy), 6u));
        }
    } else {
        if (pixelNoise() >= seen) {
            discard;
        }
        // Here the crowns' frame is the line of sight's: "down" the ground normal's
        // opposite across the ray, where the nearer crowns are.
        vec3 level = normal - toEye * dot(toEye, normal);
        down = length(level) > 1e-4 ? -normalize(level) : down;
        right = normalize(cross(down, toEye));
        float occluding = stems * uCrown.z * tanZenith;
        disc = visibleCrownPoint(unitHash(uvec2(gl_FragCoord.xy), 5u),
                                 unitHash(uvec2(gl_FragCoord.xy), 6u), occluding);
    }
    outAlbedo = vec4(cover.rgb * uTone * brightness, uAmbientOcclusion);
    outNormal = vec4(crownNormal(disc, right, down, toEye), 2.0);  // material 2: leaves
}
