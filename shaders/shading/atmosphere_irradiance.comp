#version 450 core
// Sky irradiance LUT: the irradiance (per unit sun illuminance) of a horizontal surface
// at radius r from the whole sky (single + multiple scattering, no direct sun), for the
// sun at cosine muSun: the upper hemisphere of sky radiance weighted by cos(zenith).
// The ground shading's sky light comes from it (replacing the former constant factor).
// Computed once per set of atmosphere parameters, after the transmittance and
// multiple-scattering LUTs.
#include "atmosphere_model.glsl"
#include "atmosphere_integrate.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba32f, binding = 0) uniform writeonly image2D uOutput;

const int ZENITH_STEPS = 8;
const int AZIMUTH_STEPS = 8;  // over 0 .. pi; the sky is symmetric about the sun's plane
const int STEPS = 24;

void main() {
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(texel, IRRADIANCE_SIZE))) {
        return;
    }
    float muSun = texelToUnit((float(texel.x) + 0.5) / float(IRRADIANCE_SIZE.x),
                              float(IRRADIANCE_SIZE.x)) * 2.0 - 1.0;
    float height = texelToUnit((float(texel.y) + 0.5) / float(IRRADIANCE_SIZE.y),
                               float(IRRADIANCE_SIZE.y)) * (uTopRadius - uBottomRadius);
    vec3 origin = vec3(0.0, 0.0, uBottomRadius + max(height, 1.0));
    vec3 sun = vec3(sqrt(max(1.0 - muSun * muSun, 0.0)), 0.0, muSun);
    float dZenith = 0.5 * PI / float(ZENITH_STEPS);
    float dAzimuth = PI / float(AZIMUTH_STEPS);
    vec3 irradiance = vec3(0.0);
    for (int i = 0; i < ZENITH_STEPS; ++i) {
        float zenith = (float(i) + 0.5) * dZenith;
        for (int j = 0; j < AZIMUTH_STEPS; ++j) {
            float azimuth = (float(j) + 0.5) * dAzimuth;
            vec3 direction = vec3(sin(zenith) * cos(azimuth), sin(zenith) * sin(azimuth),
                                  cos(zenith));
            vec3 radiance, transmittance;
            integrateScattering(origin, direction, sun, STEPS, radiance, transmittance);
            // Both halves of the azimuth circle: x 2.
            irradiance += 2.0 * radiance * cos(zenith) * sin(zenith) * dZenith * dAzimuth;
        }
    }
    imageStore(uOutput, texel, vec4(irradiance, 1.0));
}
