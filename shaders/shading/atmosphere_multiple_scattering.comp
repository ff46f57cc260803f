#version 450 core
// Multiple-scattering LUT (Hillaire 2020 §5.1, eq. 5-9): at radius r with the sun at
// cosine muSun, the second-order light L_2 and the transfer factor f_ms, both integrated
// over the sphere of directions with an isotropic phase function; Psi_ms = L_2 / (1 -
// f_ms) sums all orders >= 2. The planet's ground reflects with uGroundAlbedo (Lambert).
// Computed once per set of atmosphere parameters, after the transmittance LUT.
#include "atmosphere_model.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(rgba32f, binding = 0) uniform writeonly image2D uOutput;
uniform sampler2D uTransmittanceLut;

const int DIRECTIONS = 128;
const int STEPS = 20;

vec3 sphereDirection(int i) {
    float z = 1.0 - (2.0 * float(i) + 1.0) / float(DIRECTIONS);
    float radius = sqrt(max(0.0, 1.0 - z * z));
    float phi = float(i) * PI * (3.0 - sqrt(5.0));
    return vec3(radius * cos(phi), radius * sin(phi), z);
}

void main() {
    ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
    if (any(greaterThanEqual(texel, MULTIPLE_SCATTERING_SIZE))) {
        return;
    }
    vec2 unit = vec2(texelToUnit((float(texel.x) + 0.5) / float(MULTIPLE_SCATTERING_SIZE.x),
                                 float(MULTIPLE_SCATTERING_SIZE.x)),
                     texelToUnit((float(texel.y) + 0.5) / float(MULTIPLE_SCATTERING_SIZE.y),
                                 float(MULTIPLE_SCATTERING_SIZE.y)));
    float muSun = unit.x * 2.0 - 1.0;
    float r = uBottomRadius + max(unit.y * (uTopRadius - uBottomRadius), 1.0);
    vec3 origin = vec3(0.0, 0.0, r);
    vec3 sun = vec3(sqrt(max(1.0 - muSun * muSun, 0.0)), 0.0, muSun);
    vec3 secondOrder = vec3(0.0);
    vec3 transfer = vec3(0.0);
    for (int d = 0; d < DIRECTIONS; ++d) {
        vec3 direction = sphereDirection(d);
        vec2 shell = raySphere(origin, direction, uTopRadius);
        vec2 planet = raySphere(origin, direction, uBottomRadius);
        bool ground = planet.x < planet.y && planet.x > 0.0;
        float rayLength = ground ? planet.x : max(shell.y, 0.0);
        float dt = rayLength / float(STEPS);
        vec3 throughput = vec3(1.0);
        for (int i = 0; i < STEPS; ++i) {
            vec3 point = origin + direction * ((float(i) + 0.5) * dt);
            float pointRadius = length(point);
            Medium m = mediumAt(pointRadius - uBottomRadius);
            vec3 scattering = m.rayleighScattering + m.mieScattering;
            vec3 stepTransmittance = exp(-m.extinction * dt);
            vec3 integral = throughput * scattering * (1.0 - stepTransmittance) /
                            max(m.extinction, vec3(1e-12));
            vec3 sunLight =
                sunTransmittance(uTransmittanceLut, pointRadius, dot(point / pointRadius, sun));
            secondOrder += integral * sunLight / (4.0 * PI);
            transfer += integral;
            throughput *= stepTransmittance;
        }
        if (ground) {
            vec3 point = origin + direction * rayLength;
            vec3 normal = normalize(point);
            float muGround = dot(normal, sun);
            secondOrder += throughput * sunTransmittance(uTransmittanceLut, uBottomRadius, muGround) *
                           max(muGround, 0.0) * uGroundAlbedo / PI;
        }
    }
    secondOrder /= float(DIRECTIONS);
    transfer /= float(DIRECTIONS);
    imageStore(uOutput, texel, vec4(secondOrder / (1.0 - transfer), 1.0));
}
