#version 450 core
// Sky-view LUT (Hillaire 2020 §5.2): the sky's scattered radiance (per unit sun
// illuminance, no sun disc) over all view directions from the camera's radius, in a local
// frame with the zenith on +z and the sun in the x-z plane. Computed per frame.
#include "atmosphere_model.glsl"
#include "atmosphere_integrate.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba32f, binding = 0) uniform writeonly image2D uOutput;
uniform float uViewRadius;  // metres, inside the atmosphere
uniform float uSunZenithCos;

const int STEPS = 30;

void main() {
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(texel, SKY_VIEW_SIZE))) {
        return;
    }
    vec2 angles = skyViewAngles(uViewRadius, (vec2(texel) + 0.5) / vec2(SKY_VIEW_SIZE));
    vec3 direction = vec3(sin(angles.x) * cos(angles.y), sin(angles.x) * sin(angles.y),
                          cos(angles.x));
    vec3 sun = vec3(sqrt(max(1.0 - uSunZenithCos * uSunZenithCos, 0.0)), 0.0, uSunZenithCos);
    vec3 radiance, transmittance;
    integrateScattering(vec3(0.0, 0.0, uViewRadius), direction, sun, STEPS, radiance,
                        transmittance);
    imageStore(uOutput, texel, vec4(radiance, 1.0));
}
