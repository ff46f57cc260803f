#version 450 core
// The shading pass: the only place light is computed. Reads the G-buffer (albedo and
// ambient occlusion, normal, reversed-Z depth), lights terrain and plants by the sun and
// sky, adds aerial perspective and the sky from the atmosphere model, tone maps and writes
// sRGB (and, when the target has a second attachment, the exposed linear radiance).
#include "atmosphere_lookup.glsl"
#include "shadows.glsl"
#include "schlick_brdf.glsl"

layout(location = 0) in vec2 vUv;
layout(location = 0) out vec4 outColor;
layout(location = 1) out vec4 outRadiance;  // linear, after exposure (EXR output)

uniform sampler2D uAlbedo;
uniform sampler2D uNormal;
uniform sampler2D uDepth;
uniform vec2 uProjectionScale;   // projection[0][0], projection[1][1]
uniform vec2 uProjectionOffset;  // projection[2][0], projection[2][1]: lens shift + sub-pixel sample shift
uniform float uNear;            // metres
uniform mat3 uViewToEcef;
uniform vec3 uCameraEcef;       // metres (float precision is plenty for the sky)
uniform vec3 uSunView;          // unit vector towards the sun, view space
uniform vec3 uSunEcef;
uniform bool uAtmosphere;
uniform sampler2D uAmbientOcclusion;  // screen-space (AmbientOcclusionPass), r
uniform bool uHasAmbientOcclusion;
uniform float uExposure;  // 1 / (1.2 * 2^EV100) x the project's exposure scale
uniform bool uSunVisibilityOutput;  // ShadingSettings::sunVisibilityOutput

// Materials of the G-buffer (normal.w, rounded): 0 ground (terrain.frag), 1 water
// (terrain.frag), 2 leaves (every plant shader in shaders/vegetation: ellipsoids, lines,
// meshes, billboard clouds, impostors, points, the far-field canopy; their branches too),
// 3 built objects (objects/mesh.frag). Schlick roughness r and normal-incidence reflectance f0 of each
// non-water material: soil and grass are nearly matte (r 0.8), leaves have a waxy
// cuticle (r 0.5), paint, tiles and metal sheet of buildings and turbines r 0.6; f0 0.04
// for a dielectric of refractive index ~1.5 ((n - 1)² / (n + 1)²).
const vec2 MATERIAL_ROUGHNESS_F0[4] =
    vec2[4](vec2(0.8, 0.04), vec2(0.05, 0.02), vec2(0.5, 0.04), vec2(0.6, 0.04));

// Concave curvature (1 / metres) of the terrain at `pixel` for the shadow lookup's curved
// receiver (shadows.glsl): from the four neighbouring pixels of the same terrain material,
// κ = −(n_q − n) · (p_q − p) / |p_q − p|² (normals converging over a valley), the largest;
// 0 where the ground is convex or planar. Plants (noisy per-cell normals) and built
// objects (planar faces) keep 0: their receiver plane holds.
float concaveCurvature(ivec2 pixel, vec3 positionView, vec3 normal, int material) {
    if (material > 1) {
        return 0.0;
    }
    float curvature = 0.0;
    const ivec2 steps[4] = ivec2[4](ivec2(1, 0), ivec2(-1, 0), ivec2(0, 1), ivec2(0, -1));
    vec2 size = vec2(textureSize(uDepth, 0));
    for (int k = 0; k < 4; ++k) {
        ivec2 q = pixel + steps[k];
        float depth = texelFetch(uDepth, q, 0).r;
        vec4 normalMaterial = texelFetch(uNormal, q, 0);
        if (depth <= 0.0 || any(lessThan(q, ivec2(0))) || any(greaterThanEqual(q, ivec2(size))) ||
            int(normalMaterial.w + 0.5) > 1) {
            continue;
        }
        vec2 ndc = (vec2(q) + 0.5) / size * 2.0 - 1.0;
        vec3 direction = normalize(vec3((ndc + uProjectionOffset) / uProjectionScale, -1.0));
        vec3 gap = direction * ((uNear / depth) / -direction.z) - positionView;
        float turn = -dot(normalize(normalMaterial.xyz) - normal, gap);
        curvature = max(curvature, turn / max(dot(gap, gap), 1e-6));
    }
    return curvature;
}

vec3 linearToSrgb(vec3 c) {
    c = clamp(c, 0.0, 1.0);
    return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(vec3(0.0031308), c));
}

void main() {
    ivec2 pixel = ivec2(gl_FragCoord.xy);
    float depth = texelFetch(uDepth, pixel, 0).r;
    vec2 ndc = vUv * 2.0 - 1.0;
    vec3 directionView = normalize(vec3((ndc + uProjectionOffset) / uProjectionScale, -1.0));
    vec3 directionEcef = normalize(uViewToEcef * directionView);
    vec3 origin = toSphereSpace(uCameraEcef);
    vec3 direction = normalize(toSphereSpace(directionEcef));
    vec3 sun = normalize(toSphereSpace(uSunEcef));

    vec3 radiance;
    if (depth > 0.0) {
        vec4 albedo = texelFetch(uAlbedo, pixel, 0);
        vec4 normalMaterial = texelFetch(uNormal, pixel, 0);
        vec3 normal = normalize(normalMaterial.xyz);
        float distance = (uNear / depth) / -directionView.z;
        vec3 surfaceEcef = uCameraEcef + directionEcef * distance;
        vec3 upView = normalize(transpose(uViewToEcef) * normalize(surfaceEcef));
        vec3 surfaceSphere = toSphereSpace(surfaceEcef);
        float sunDiffuse = max(dot(normal, uSunView), 0.0);
        // Sun and sky light from the atmosphere model (Hillaire 2020): the sun through the
        // transmittance LUT, the sky from the irradiance LUT of a horizontal surface,
        // tilted with the normal (isotropic sky: (1 + n.up) / 2).
        vec3 sunLight = atmosphereSunIlluminance(surfaceSphere, sun);
        // Cascaded shadow maps (seed 001 §7.1): 0 in the shadow of terrain, plants, objects.
        int material = clamp(int(normalMaterial.w + 0.5), 0, 3);
        float visibility =
            sunVisibility(directionEcef * distance, normalize(uViewToEcef * normal),
                          concaveCurvature(pixel, directionView * distance, normal, material));
        if (uSunVisibilityOutput) {
            outRadiance = vec4(vec3(visibility), 1.0);
            outColor = vec4(vec3(visibility), 1.0);
            return;
        }
        sunLight *= visibility;
        // albedo.a: ambient occlusion (1 for terrain; per primitive for plants, §6.5),
        // times the screen-space occlusion (seed 001 §7.1) where it is computed: sky
        // light only, the sun has its shadow maps.
        float occlusion = albedo.a;
        if (uHasAmbientOcclusion) {
            occlusion *= texelFetch(uAmbientOcclusion, pixel, 0).r;
        }
        vec3 ambient = atmosphereSkyIrradiance(surfaceSphere, sun) * (0.5 + 0.5 * dot(normal, upView)) *
                       occlusion;
        vec3 surface;
        if (material != 1) {
            // Sunlight through Schlick's BRDF (seed 001 §7.1); skylight Lambertian (the
            // sky is a broad source: the specular lobe averages out).
            vec2 roughnessF0 = MATERIAL_ROUGHNESS_F0[material];
            surface = schlickBrdf(albedo.rgb, roughnessF0.x, roughnessF0.y, normal, uSunView,
                                  -directionView) *
                          sunLight * sunDiffuse +
                      albedo.rgb / PI * ambient;
        } else {  // water: Lambertian body, sun glint and a little sky reflection
            surface = albedo.rgb / PI * (sunLight * sunDiffuse + ambient);
            vec3 reflected = reflect(directionView, normal);
            float glint = pow(max(dot(reflected, uSunView), 0.0), 1500.0) * 6.0;
            float fresnel = 0.02 + 0.98 * pow(1.0 - max(dot(-directionView, normal), 0.0), 5.0);
            surface += sunLight * glint * fresnel + ambient / PI * fresnel;
        }
        if (uAtmosphere) {
            vec3 inscattered, transmittance;
            atmosphereAerialPerspective(vUv, origin, direction, sun, distance, inscattered, transmittance);
            radiance = surface * transmittance + inscattered;
        } else {
            radiance = surface;
        }
    } else if (uSunVisibilityOutput) {
        outRadiance = vec4(1.0);
        outColor = vec4(1.0);
        return;
    } else {
        radiance = uAtmosphere ? atmosphereSky(origin, direction, sun) : vec3(0.0);
    }
    vec3 exposed = uExposure * radiance;
    outRadiance = vec4(exposed, 1.0);
    vec3 mapped = 1.0 - exp(-exposed);
    outColor = vec4(linearToSrgb(mapped), 1.0);
}
