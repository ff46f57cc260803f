// The shading pass's view of the atmosphere LUTs (Hillaire 2020, "A Scalable and
// Production Ready Sky and Atmosphere Rendering Technique"): sun and sky light for the
// ground from the transmittance and sky-irradiance LUTs, aerial perspective from the
// froxel volume, the sky from the sky-view LUT (camera inside the atmosphere) or a short
// ray march through the LUTs (camera in space, where the sky-view parameterisation does
// not hold), and the limb-darkened sun disc. Everything in sphere space (see
// atmosphere_model.glsl); radiance in cd/m^2, illuminance in lux.
#include "atmosphere_model.glsl"
#include "atmosphere_integrate.glsl"

uniform sampler2D uIrradianceLut;
uniform sampler2D uSkyViewLut;
uniform sampler3D uAerialInscattered;
uniform sampler3D uAerialTransmittance;
uniform vec3 uSunIlluminance;  // lux at the top of the atmosphere, linear RGB
uniform float uSunLimbDarkening;
uniform float uAerialNear;   // metres, as the aerial-perspective pass
uniform float uAerialRange;  // metres

const int SPACE_SKY_STEPS = 32;

// Illuminance of a surface facing the sun at `point`: the sun's light after the
// atmosphere and behind the planet's horizon.
vec3 atmosphereSunIlluminance(vec3 point, vec3 sun) {
    float r = length(point);
    return uSunIlluminance * sunTransmittance(uTransmittanceLut, r, dot(point / r, sun));
}

// Irradiance of a horizontal surface at `point` from the sky (no direct sun).
vec3 atmosphereSkyIrradiance(vec3 point, vec3 sun) {
    float r = length(point);
    return uSunIlluminance * textureLod(uIrradianceLut, irradianceUv(r, dot(point / r, sun)), 0.0).rgb;
}

// Aerial perspective between the camera and a surface `distance` metres along the
// pixel's ray (screen position uv): scattered radiance and transmittance.
// From above the atmosphere the froxel slices are too coarse near the ground (rings
// around the nadir): there each pixel marches through the LUTs instead, from where its
// ray enters the atmosphere (Hillaire §5.3 does the same for space views).
void atmosphereAerialPerspective(vec2 uv, vec3 origin, vec3 direction, vec3 sun, float distance,
                                 out vec3 inscattered, out vec3 transmittance) {
    if (length(origin) >= uTopRadius - 10.0) {
        integrateScatteringTo(origin, direction, sun, distance, SPACE_SKY_STEPS, true, inscattered,
                              transmittance);
        inscattered *= uSunIlluminance;
        return;
    }
    vec2 shell = raySphere(origin, direction, uTopRadius);
    float start = max(shell.x, 0.0);
    float s = log(1.0 + max(distance - start, 0.0) / uAerialNear) /
              log(1.0 + uAerialRange / uAerialNear);
    float slices = float(textureSize(uAerialInscattered, 0).z);
    vec3 coordinate = vec3(uv, unitToTexel(clamp(s, 0.0, 1.0), slices));
    inscattered = uSunIlluminance * textureLod(uAerialInscattered, coordinate, 0.0).rgb;
    transmittance = textureLod(uAerialTransmittance, coordinate, 0.0).rgb;
}

// The sun's disc with limb darkening I(mu) = 1 - u (1 - mu), mu the cosine on the solar
// surface, normalised so the disc's illuminance is uSunIlluminance.
vec3 sunDisc(vec3 direction, vec3 sun) {
    float angle = acos(clamp(dot(direction, sun), -1.0, 1.0));
    if (angle >= uSunAngularRadius) {
        return vec3(0.0);
    }
    float rho = angle / uSunAngularRadius;
    float limb = 1.0 - uSunLimbDarkening * (1.0 - sqrt(max(1.0 - rho * rho, 0.0)));
    float solidAngle = PI * uSunAngularRadius * uSunAngularRadius;
    return uSunIlluminance * limb / (solidAngle * (1.0 - uSunLimbDarkening / 3.0));
}

// Radiance of the sky (no terrain drawn) along `direction` from `origin`.
vec3 atmosphereSky(vec3 origin, vec3 direction, vec3 sun) {
    float r = length(origin);
    vec3 up = origin / r;
    vec2 planet = raySphere(origin, direction, uBottomRadius);
    bool hitsPlanet = planet.x < planet.y && planet.x > 0.0;
    vec3 radiance;
    vec3 transmittance;
    if (r < uTopRadius - 10.0) {
        float zenithCos = dot(direction, up);
        vec3 viewHorizontal = direction - up * zenithCos;
        vec3 sunHorizontal = sun - up * dot(sun, up);
        float cosAzimuth = dot(viewHorizontal, sunHorizontal) /
                           max(length(viewHorizontal) * length(sunHorizontal), 1e-12);
        float azimuth = acos(clamp(cosAzimuth, -1.0, 1.0));
        radiance = textureLod(uSkyViewLut, skyViewUv(r, zenithCos, azimuth), 0.0).rgb;
        transmittance = transmittanceToTop(uTransmittanceLut, r, zenithCos);
    } else {
        integrateScattering(origin, direction, sun, SPACE_SKY_STEPS, radiance, transmittance);
    }
    radiance *= uSunIlluminance;
    if (!hitsPlanet) {
        radiance += sunDisc(direction, sun) * transmittance;
    }
    return radiance;
}
