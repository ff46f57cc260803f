#version 450 core
// Ray-cast ellipsoid fragment (seed 001 §6.4.1): the pixel's view ray starts where it
// crosses the plane in front of the ellipsoid (ellipsoid.vert), is intersected in the
// unit-sphere frame relative to the centre; depth from the hit (reversed-Z: near /
// distance along -z), declared depth_less because the hit is never nearer than the
// sprite's depth (the ellipsoid's nearest point); the noise alpha test of §3.4.1 with
// its cell count limited by the screen-space derivative (the mip level fwidth allows);
// a perforated front hit goes on to the back hit, tested again (§3.4.1 as calibrated by
// PrimitiveRasterizer); normal perturbed by the noise; screen-door LoD fades.
#include "vegetation.glsl"
#include "farfield_fade.glsl"

layout(location = 0) flat in mat3 vToLocal;
layout(location = 3) flat in vec3 vLocalCenter;
layout(location = 4) flat in vec4 vPlane;
layout(location = 5) flat in vec4 vColorAo;
layout(location = 6) flat in vec4 vFadeNoise;
layout(location = 7) flat in uvec2 vSeedDither;

uniform mat4 uProjection;
uniform vec2 uViewport;  // pixels
uniform float uNear;
uniform float uNormalNoise;  // strength of the normal perturbation

layout(location = 0) out vec4 outAlbedo;  // rgb: linear albedo, a: ambient occlusion
layout(location = 1) out vec4 outNormal;  // xyz: view-space normal, w: material (0)
layout(depth_less) out float gl_FragDepth;

void main() {
    // The pixel's view ray (perspective, possibly off-axis: ndc = scale * x / -z - offset,
    // the offset uProjection[2].xy holding a lens shift and the sub-pixel shift of an
    // anti-aliasing sample) and its crossing with the plane.
    vec2 ndc = gl_FragCoord.xy / uViewport * 2.0 - 1.0;
    vec3 ray = vec3((ndc.x + uProjection[2][0]) / uProjection[0][0],
                    (ndc.y + uProjection[2][1]) / uProjection[1][1], -1.0);
    float across = dot(ray, vPlane.xyz);
    vec3 start = ray * (vPlane.w / max(across, 1e-6));  // view space, on the plane
    vec3 localDirection = vToLocal * start;
    vec3 localOrigin = localDirection - vLocalCenter;
    // Closest approach of the ray to the centre, then back along the ray to the surface.
    float a = dot(localDirection, localDirection);
    float along = -dot(localOrigin, localDirection) / a;
    vec3 closest = localOrigin + along * localDirection;
    float discriminant = 1.0 - dot(closest, closest);
    float back = sqrt(max(discriminant, 0.0) / a);
    vec3 q = closest - back * localDirection;  // hit point on the unit sphere
    float t = along - back;                    // ray: start × (1 + t)
    // Derivatives before any discard (they need the whole pixel quad).
    vec3 width = fwidth(q);
    float footprint = max(max(width.x, width.y), width.z);
    if (discriminant < 0.0 || t < -1.0 || across <= 0.0) {
        discard;
    }
    if (farFieldCanopyPixel()) {
        discard;  // the far-field canopy has this pixel (farfield_fade.glsl)
    }
    float dither = ditherValue(gl_FragCoord.xy, uintBitsToFloat(vSeedDither.y));
    if (dither >= vFadeNoise.x || dither < vFadeNoise.y) {
        discard;
    }
    // Noise cells: the stored level, capped where a cell would be under ~2 pixels.
    float cells = vFadeNoise.z;
    if (footprint > 0.0) {
        cells = min(cells, exp2(floor(log2(max(1.0 / footprint, 1.0)))));
    }
    // The seed comes from the ellipsoid's centre in the model, so every instance of a
    // species shares its pattern. With the level's cells that is harmless (each crown
    // still shows many cells); once capped, a cell spans much of the ellipsoid and the
    // shared pattern decided it for every tree alike: at one cell the coarse levels'
    // perforated ellipsoids were missing from every tree of the species, and the front
    // and back hits shared one test (opacity 1 − t, not 1 − t²), so stands of one- and
    // two-pixel trees showed about half their cover (the band at 2–6 km in the demo's
    // `lookout`, docs/benchmarks.md, vegetation). Capped, each instance (its dither
    // bits) draws its own pattern and the back hit its own test.
    uint frontSeed = vSeedDither.x;
    uint backSeed = frontSeed;
    if (cells < vFadeNoise.z) {
        frontSeed ^= vSeedDither.y * 0x9E3779B9u;
        backSeed = frontSeed ^ 0x5BD1E995u;
    }
    q = clamp(q, -1.0, 1.0);
    if (vFadeNoise.w > 0.0 && ellipsoidNoise(q, cells, frontSeed) < vFadeNoise.w) {
        // Perforated front: the ray goes on to the back of the ellipsoid, which the noise
        // tests again (as PrimitiveRasterizer, whose images calibrated the level's
        // threshold and scale: a ray through the crown meets two layers, opacity 1 − t²
        // where one test gave 1 − t and coarse levels drew ~60 % of their coverage).
        q = clamp(closest + back * localDirection, -1.0, 1.0);
        t = along + back;
        if (ellipsoidNoise(q, cells, backSeed) < vFadeNoise.w) {
            discard;
        }
    }
    vec3 hit = start * (1.0 + t);
    gl_FragDepth = uNear / max(-hit.z, uNear);
    vec3 perturb = ellipsoidNoise3(q, cells, frontSeed ^ 0x68E31DA4u) - 0.5;
    vec3 normal = normalize(transpose(vToLocal) * normalize(q + uNormalNoise * perturb));
    if (dot(normal, hit) > 0.0) {
        normal = -normal;
    }
    outAlbedo = vColorAo;
    outNormal = vec4(normal, 2.0);  // material 2: leaves (shade.frag)
}
