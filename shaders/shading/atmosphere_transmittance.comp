#version 450 core
// Transmittance LUT (Hillaire 2020 §4; parameterisation of Bruneton & Neyret 2008 as in
// Bruneton 2017): transmittance from radius r to the top of the atmosphere along cosine
// mu. Computed once per set of atmosphere parameters.
#include "atmosphere_model.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba32f, binding = 0) uniform writeonly image2D uOutput;

const int STEPS = 128;

void main() {
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(texel, TRANSMITTANCE_SIZE))) {
        return;
    }
    vec2 rMu = transmittanceRadiusMu((vec2(texel) + 0.5) / vec2(TRANSMITTANCE_SIZE));
    vec3 origin = vec3(0.0, 0.0, rMu.x);
    vec3 direction = vec3(sqrt(max(1.0 - rMu.y * rMu.y, 0.0)), 0.0, rMu.y);
    float rayLength = max(raySphere(origin, direction, uTopRadius).y, 0.0);
    float dt = rayLength / float(STEPS);
    vec3 depth = vec3(0.0);
    for (int i = 0; i < STEPS; ++i) {
        vec3 point = origin + direction * ((float(i) + 0.5) * dt);
        depth += mediumAt(length(point) - uBottomRadius).extinction * dt;
    }
    imageStore(uOutput, texel, vec4(exp(-depth), 1.0));
}
