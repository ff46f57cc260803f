// The physical atmosphere shared by the LUT passes and the shading pass (Hillaire 2020,
// "A Scalable and Production Ready Sky and Atmosphere Rendering Technique", EGSR 2020;
// density profiles and the transmittance parameterisation of Bruneton & Neyret 2008,
// "Precomputed Atmospheric Scattering", as in Bruneton's 2017 reference code).
// Positions are in the sphere space of the shading: ECEF metres with z scaled by a/b, so
// the WGS84 ellipsoid is the sphere of radius uBottomRadius (= a). Radiances in the LUTs
// are per unit solar illuminance (the shading multiplies by uSunIlluminance, lux).
// Parameters come from AtmosphereParameters (core/atmosphere) through
// AtmosphereUniforms (render/shading).
#include "../common/constants.glsl"

uniform float uBottomRadius;
uniform float uTopRadius;
uniform vec3 uRayleighScattering;  // per metre at the ground
uniform float uRayleighScaleHeight;
uniform float uMieScattering;
uniform float uMieExtinction;
uniform float uMieScaleHeight;
uniform float uMieAsymmetry;
uniform vec3 uOzoneAbsorption;
uniform float uOzoneCentre;
uniform float uOzoneHalfWidth;
uniform float uGroundAlbedo;
uniform float uSunAngularRadius;

const ivec2 TRANSMITTANCE_SIZE = ivec2(256, 64);
const ivec2 MULTIPLE_SCATTERING_SIZE = ivec2(128, 32);
const ivec2 IRRADIANCE_SIZE = ivec2(64, 16);
const ivec2 SKY_VIEW_SIZE = ivec2(192, 108);

vec3 toSphereSpace(vec3 ecef) {
    return vec3(ecef.xy, ecef.z * (WGS84_A / WGS84_B));
}

vec3 fromSphereSpace(vec3 sphere) {
    return vec3(sphere.xy, sphere.z * (WGS84_B / WGS84_A));
}

// Ray/sphere intersection distances (near, far); near > far when missed.
vec2 raySphere(vec3 origin, vec3 direction, float radius) {
    float b = dot(origin, direction);
    // |o|^2 - r^2 as (|o| - r)(|o| + r): keeps precision near the surface in float.
    float lengthOrigin = length(origin);
    float c = (lengthOrigin - radius) * (lengthOrigin + radius);
    float discriminant = b * b - c;
    if (discriminant < 0.0) {
        return vec2(1.0, -1.0);
    }
    float s = sqrt(discriminant);
    return vec2(-b - s, -b + s);
}

struct Medium {
    vec3 rayleighScattering;
    vec3 mieScattering;
    vec3 extinction;
};

Medium mediumAt(float height) {
    float rayleigh = exp(-max(height, -1000.0) / uRayleighScaleHeight);
    float mie = exp(-max(height, -1000.0) / uMieScaleHeight);
    float ozone = max(0.0, 1.0 - abs(height - uOzoneCentre) / uOzoneHalfWidth);
    Medium m;
    m.rayleighScattering = uRayleighScattering * rayleigh;
    m.mieScattering = vec3(uMieScattering * mie);
    m.extinction = m.rayleighScattering + vec3(uMieExtinction * mie) + uOzoneAbsorption * ozone;
    return m;
}

float rayleighPhase(float mu) {
    return 3.0 / (16.0 * PI) * (1.0 + mu * mu);
}

// Cornette & Shanks 1992.
float miePhase(float mu) {
    float g = uMieAsymmetry;
    float g2 = g * g;
    return 3.0 / (8.0 * PI) * (1.0 - g2) * (1.0 + mu * mu) /
           ((2.0 + g2) * pow(max(1.0 + g2 - 2.0 * g * mu, 1e-6), 1.5));
}

// Texture coordinate of x in [0, 1] on a texture of `size` texels, mapped to texel
// centres (Bruneton 2017, GetTextureCoordFromUnitRange) and back.
float unitToTexel(float x, float size) {
    return 0.5 / size + x * (1.0 - 1.0 / size);
}
float texelToUnit(float u, float size) {
    return (u - 0.5 / size) / (1.0 - 1.0 / size);
}

// Transmittance LUT parameterisation (Bruneton 2017): x_r = rho / H, x_mu = distance to
// the top boundary, normalised between its minimum and the horizon's.
vec2 transmittanceUv(float r, float mu) {
    float top = uTopRadius, bottom = uBottomRadius;
    float H = sqrt((top - bottom) * (top + bottom));
    float rho = sqrt(max((r - bottom) * (r + bottom), 0.0));
    float discriminant = (top - r) * (top + r) + r * r * mu * mu;
    float d = max(0.0, -r * mu + sqrt(max(discriminant, 0.0)));
    float dMin = top - r;
    float dMax = rho + H;
    float xMu = clamp((d - dMin) / max(dMax - dMin, 1e-3), 0.0, 1.0);
    float xR = clamp(rho / H, 0.0, 1.0);
    return vec2(unitToTexel(xMu, float(TRANSMITTANCE_SIZE.x)),
                unitToTexel(xR, float(TRANSMITTANCE_SIZE.y)));
}

// Inverse of transmittanceUv: (r, mu) of a texel centre.
vec2 transmittanceRadiusMu(vec2 uv) {
    float top = uTopRadius, bottom = uBottomRadius;
    float xMu = texelToUnit(uv.x, float(TRANSMITTANCE_SIZE.x));
    float xR = texelToUnit(uv.y, float(TRANSMITTANCE_SIZE.y));
    float H = sqrt((top - bottom) * (top + bottom));
    float rho = H * xR;
    float r = sqrt(rho * rho + bottom * bottom);
    float dMin = top - r;
    float dMax = rho + H;
    float d = dMin + xMu * (dMax - dMin);
    float mu = d == 0.0 ? 1.0 : (H * H - rho * rho - d * d) / (2.0 * r * d);
    return vec2(r, clamp(mu, -1.0, 1.0));
}

// Multiple-scattering LUT (Hillaire §5.1): u = cos(sun zenith), v = height.
vec2 multipleScatteringUv(float r, float muSun) {
    float x = clamp(muSun * 0.5 + 0.5, 0.0, 1.0);
    float y = clamp((r - uBottomRadius) / (uTopRadius - uBottomRadius), 0.0, 1.0);
    return vec2(unitToTexel(x, float(MULTIPLE_SCATTERING_SIZE.x)),
                unitToTexel(y, float(MULTIPLE_SCATTERING_SIZE.y)));
}

// Sky irradiance LUT: same axes as the multiple-scattering LUT.
vec2 irradianceUv(float r, float muSun) {
    float x = clamp(muSun * 0.5 + 0.5, 0.0, 1.0);
    float y = clamp((r - uBottomRadius) / (uTopRadius - uBottomRadius), 0.0, 1.0);
    return vec2(unitToTexel(x, float(IRRADIANCE_SIZE.x)), unitToTexel(y, float(IRRADIANCE_SIZE.y)));
}

// Fraction of the sun's disc above the horizon seen from radius r (a smooth step over
// the disc's angular diameter), so the sun sets behind the planet gradually.
float sunAboveHorizon(float r, float muSun) {
    float sinHorizon = uBottomRadius / r;
    float muHorizon = -sqrt(max(1.0 - sinHorizon * sinHorizon, 0.0));
    float radius = uSunAngularRadius * sqrt(max(1.0 - muHorizon * muHorizon, 0.0));
    return smoothstep(-radius, radius, muSun - muHorizon);
}

vec3 transmittanceToTop(sampler2D lut, float r, float mu) {
    return textureLod(lut, transmittanceUv(r, mu), 0.0).rgb;
}

// Transmittance of sunlight reaching radius r with the sun at cosine muSun (planet
// shadow included).
vec3 sunTransmittance(sampler2D lut, float r, float muSun) {
    return transmittanceToTop(lut, r, muSun) * sunAboveHorizon(r, muSun);
}

vec3 multipleScatteringAt(sampler2D lut, float r, float muSun) {
    return textureLod(lut, multipleScatteringUv(r, muSun), 0.0).rgb;
}

// Sky-view LUT (Hillaire §5.2): u = azimuth from the sun's vertical plane, 0 .. pi (the
// sky is symmetric about it); v = view zenith angle, non-linear so the horizon gets the
// most texels: v < 0.5 above the horizon, v > 0.5 below (towards the planet).
vec2 skyViewUv(float r, float viewZenithCos, float azimuth) {
    float sinBeta = clamp(uBottomRadius / r, 0.0, 1.0);
    float beta = asin(sinBeta);  // angular radius of the planet below the horizon
    float zenithHorizonAngle = PI - beta;
    float viewZenith = acos(clamp(viewZenithCos, -1.0, 1.0));
    float v;
    if (viewZenith < zenithHorizonAngle) {
        float coord = viewZenith / zenithHorizonAngle;
        coord = 1.0 - sqrt(max(1.0 - coord, 0.0));
        v = coord * 0.5;
    } else {
        float coord = (viewZenith - zenithHorizonAngle) / max(beta, 1e-6);
        v = sqrt(clamp(coord, 0.0, 1.0)) * 0.5 + 0.5;
    }
    float u = clamp(azimuth / PI, 0.0, 1.0);
    return vec2(unitToTexel(u, float(SKY_VIEW_SIZE.x)), unitToTexel(v, float(SKY_VIEW_SIZE.y)));
}

// Inverse of skyViewUv at a texel centre: (view zenith angle, azimuth).
vec2 skyViewAngles(float r, vec2 uv) {
    float u = texelToUnit(uv.x, float(SKY_VIEW_SIZE.x));
    float v = texelToUnit(uv.y, float(SKY_VIEW_SIZE.y));
    float beta = asin(clamp(uBottomRadius / r, 0.0, 1.0));
    float zenithHorizonAngle = PI - beta;
    float viewZenith;
    if (v < 0.5) {
        float coord = 1.0 - v * 2.0;
        viewZenith = zenithHorizonAngle * (1.0 - coord * coord);
    } else {
        float coord = v * 2.0 - 1.0;
        viewZenith = zenithHorizonAngle + beta * coord * coord;
    }
    return vec2(viewZenith, u * PI);
}
