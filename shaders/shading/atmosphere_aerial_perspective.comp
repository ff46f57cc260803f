#version 450 core
// Aerial-perspective volume (Hillaire 2020 §5.3): froxels over the view frustum holding
// the light scattered towards the camera (per unit sun illuminance) and the
// transmittance from the camera to each froxel depth. One invocation marches one screen
// column through all slices, so each froxel costs one step. Slices are spaced
// logarithmically in distance from where the ray enters the atmosphere,
// t = start + near ((1 + range / near)^s - 1), s = slice / (slices - 1), so the first
// kilometres get fine slices and a view from space reaches the far limb; the shading
// pass maps distances back the same way (atmosphere_lookup.glsl). Single scattering is
// multiplied by the shadow hook (shadowed in-scattering): with shadow maps, each substep
// averages SHADOW_TAPS lookups at stratified positions, offset per column by interleaved
// gradient noise (Jimenez 2014) so the steps' staircase turns into a fine dither that
// the volume's trilinear lookup smooths. Computed per frame.
#include "atmosphere_model.glsl"
#include "atmosphere_integrate.glsl"
#include "atmosphere_shadow_hook.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba32f, binding = 0) uniform writeonly image3D uInscattered;
layout(rgba32f, binding = 1) uniform writeonly image3D uTransmittance;
uniform vec3 uCameraSphere;     // camera position in sphere space, metres
uniform mat3 uViewToEcef;
uniform vec2 uProjectionScale;  // projection[0][0], projection[1][1]
uniform vec3 uSunSphere;        // unit vector towards the sun, sphere space
uniform float uAerialNear;      // metres
uniform float uAerialRange;     // metres
uniform ivec3 uFroxels;

const int SUBSTEPS = 2;
const int SHADOW_TAPS = 2;  // per substep: 4 shadow-map lookups per slice

// Interleaved gradient noise in [0, 1): a fixed dither per froxel column.
float columnJitter(ivec2 column) {
    return fract(52.9829189 * fract(dot(vec2(column), vec2(0.06711056, 0.00583715))));
}

// The sun's visible fraction over [t0, t1] of the ray (offsets from the camera).
float segmentSunVisibility(vec3 direction, float t0, float t1, float jitter) {
    if (!atmosphereHasShadows()) {
        return 1.0;
    }
    float sum = 0.0;
    for (int k = 0; k < SHADOW_TAPS; ++k) {
        float t = t0 + (t1 - t0) * (float(k) + jitter) / float(SHADOW_TAPS);
        sum += atmosphereSunVisibility(fromSphereSpace(direction * t));
    }
    return sum / float(SHADOW_TAPS);
}

float sliceDistance(float start, int slice) {
    float s = float(slice) / float(uFroxels.z - 1);
    return start + uAerialNear * (pow(1.0 + uAerialRange / uAerialNear, s) - 1.0);
}

void main() {
    ivec2 column = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(column, uFroxels.xy))) {
        return;
    }
    vec2 ndc = (vec2(column) + 0.5) / vec2(uFroxels.xy) * 2.0 - 1.0;
    vec3 directionView = normalize(vec3(ndc / uProjectionScale, -1.0));
    vec3 directionEcef = normalize(uViewToEcef * directionView);
    vec3 direction = normalize(toSphereSpace(directionEcef));
    // To the planet shrunk by 1 km (terrain below sea level), or out of the atmosphere.
    vec2 shell = raySphere(uCameraSphere, direction, uTopRadius);
    vec2 planet = raySphere(uCameraSphere, direction, uBottomRadius - 1000.0);
    float start = max(shell.x, 0.0);
    float end = planet.x < planet.y && planet.x > 0.0 ? planet.x : shell.y;
    float mu = dot(direction, uSunSphere);
    float phaseRayleigh = rayleighPhase(mu);
    float phaseMie = miePhase(mu);
    vec3 radiance = vec3(0.0);
    vec3 transmittance = vec3(1.0);
    float previous = start;
    float jitter = columnJitter(column);
    for (int slice = 0; slice < uFroxels.z; ++slice) {
        float target = min(sliceDistance(start, slice), max(end, start));
        if (shell.x <= shell.y && shell.y > 0.0 && target > previous) {
            float step = (target - previous) / float(SUBSTEPS);
            for (int i = 0; i < SUBSTEPS; ++i) {
                float t0 = previous + step * float(i);
                float t1 = t0 + step;
                float visibility = segmentSunVisibility(direction, t0, t1, jitter);
                scatterSegment(uCameraSphere, direction, t0, t1, uSunSphere, phaseRayleigh,
                               phaseMie, visibility, radiance, transmittance);
            }
            previous = target;
        }
        imageStore(uInscattered, ivec3(column, slice), vec4(radiance, 1.0));
        imageStore(uTransmittance, ivec3(column, slice), vec4(transmittance, 1.0));
    }
}
