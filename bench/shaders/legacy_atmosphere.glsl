// The single-scattering shading pass as it was before the LUT atmosphere (issue 16), kept
// only so `sylva bench shading` can time the old ray march against the LUTs
// (bench/AtmosphereBenchmark.cpp). Not used for images.
// Single-scattering atmosphere (Rayleigh + Mie, exponential density profiles) after
// Nishita et al. 1993, as seed 001 ch. 7 builds on: in-scattered light and
// transmittance along a view ray, ray-marched. The ellipsoid is made a sphere of
// radius WGS84_A by scaling z by a/b, so the shell follows the flattening.
#include "../common/constants.glsl"

const float ATMOSPHERE_TOP = WGS84_A + 80000.0;
const vec3 BETA_RAYLEIGH = vec3(5.8e-6, 13.5e-6, 33.1e-6);  // per metre at sea level
const float BETA_MIE = 21e-6;
const float HEIGHT_RAYLEIGH = 8000.0;
const float HEIGHT_MIE = 1200.0;
const float MIE_G = 0.76;
const float SUN_INTENSITY = 20.0;
// Single scattering underestimates the sky; this factor stands in for the missing
// multiple scattering (about 1.5-2x for the clear sky, Bruneton & Neyret 2008).
const float MULTIPLE_SCATTERING = 1.6;
const int VIEW_STEPS = 16;
const int SUN_STEPS = 6;

vec3 toSphereSpace(vec3 ecef) {
    return vec3(ecef.xy, ecef.z * (WGS84_A / WGS84_B));
}

// Ray/sphere intersection distances (near, far); near > far when missed.
vec2 raySphere(vec3 origin, vec3 direction, float radius) {
    float b = dot(origin, direction);
    float c = dot(origin, origin) - radius * radius;
    float discriminant = b * b - c;
    if (discriminant < 0.0) {
        return vec2(1.0, -1.0);
    }
    float s = sqrt(discriminant);
    return vec2(-b - s, -b + s);
}

vec2 densityAt(vec3 position) {
    float height = max(length(position) - WGS84_A, 0.0);
    return exp(-height / vec2(HEIGHT_RAYLEIGH, HEIGHT_MIE));
}

// Optical depth (Rayleigh, Mie) from `position` towards the sun; huge if the planet
// is in the way.
vec2 opticalDepthToSun(vec3 position, vec3 sun) {
    vec2 planet = raySphere(position, sun, WGS84_A - 2000.0);
    if (planet.x > 0.0 && planet.x < planet.y) {
        return vec2(1e9);
    }
    float exit = raySphere(position, sun, ATMOSPHERE_TOP).y;
    float step = exit / float(SUN_STEPS);
    vec2 depth = vec2(0.0);
    for (int i = 0; i < SUN_STEPS; ++i) {
        depth += densityAt(position + sun * (step * (float(i) + 0.5))) * step;
    }
    return depth;
}

vec3 extinction(vec2 opticalDepth) {
    return exp(-(BETA_RAYLEIGH * opticalDepth.x + BETA_MIE * 1.1 * opticalDepth.y));
}

// Light scattered towards the camera along origin + t * direction, t in [0, maxDistance]
// (clipped to the atmosphere), and the transmittance of that segment.
void scatter(vec3 origin, vec3 direction, float maxDistance, vec3 sun, out vec3 inscattered,
             out vec3 transmittance) {
    inscattered = vec3(0.0);
    transmittance = vec3(1.0);
    vec2 shell = raySphere(origin, direction, ATMOSPHERE_TOP);
    float start = max(shell.x, 0.0);
    float end = min(shell.y, maxDistance);
    if (end <= start) {
        return;
    }
    float step = (end - start) / float(VIEW_STEPS);
    vec2 viewDepth = vec2(0.0);
    vec3 rayleigh = vec3(0.0);
    vec3 mie = vec3(0.0);
    for (int i = 0; i < VIEW_STEPS; ++i) {
        vec3 position = origin + direction * (start + step * (float(i) + 0.5));
        vec2 density = densityAt(position) * step;
        viewDepth += density;
        vec3 attenuation = extinction(viewDepth + opticalDepthToSun(position, sun));
        rayleigh += density.x * attenuation;
        mie += density.y * attenuation;
    }
    float mu = dot(direction, sun);
    float phaseRayleigh = 3.0 / (16.0 * PI) * (1.0 + mu * mu);
    float g2 = MIE_G * MIE_G;
    float phaseMie = 3.0 / (8.0 * PI) * ((1.0 - g2) * (1.0 + mu * mu)) /
                     ((2.0 + g2) * pow(1.0 + g2 - 2.0 * MIE_G * mu, 1.5));
    inscattered = MULTIPLE_SCATTERING * SUN_INTENSITY * (rayleigh * BETA_RAYLEIGH * phaseRayleigh + mie * BETA_MIE * phaseMie);
    transmittance = extinction(viewDepth);
}
