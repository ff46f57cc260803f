// Scattering along a ray with the transmittance and multiple-scattering LUTs (Hillaire
// 2020 §4-5): single scattering with the sun's transmittance from the LUT, plus
// scattering x Psi_ms for all higher orders; each step integrated exactly for constant
// coefficients ((S - S T_step) / extinction, Hillaire §5.3). Needs atmosphere_model.glsl.

uniform sampler2D uTransmittanceLut;
uniform sampler2D uMultipleScatteringLut;

// In-scattering source (per unit sun illuminance and unit length) at `point`.
vec3 scatteringSource(vec3 point, vec3 sun, float phaseRayleigh, float phaseMie,
                      float sunVisibility, out vec3 extinction) {
    float r = length(point);
    float muSun = dot(point / r, sun);
    Medium m = mediumAt(r - uBottomRadius);
    extinction = m.extinction;
    vec3 single = (m.rayleighScattering * phaseRayleigh + m.mieScattering * phaseMie) *
                  sunTransmittance(uTransmittanceLut, r, muSun) * sunVisibility;
    vec3 multiple = (m.rayleighScattering + m.mieScattering) *
                    multipleScatteringAt(uMultipleScatteringLut, r, muSun);
    return single + multiple;
}

// Adds the segment [t0, t1] of origin + t direction to `radiance`, updating
// `transmittance` (from the ray's start to t1).
void scatterSegment(vec3 origin, vec3 direction, float t0, float t1, vec3 sun,
                    float phaseRayleigh, float phaseMie, float sunVisibility,
                    inout vec3 radiance, inout vec3 transmittance) {
    float dt = t1 - t0;
    vec3 extinction;
    vec3 source = scatteringSource(origin + direction * (0.5 * (t0 + t1)), sun, phaseRayleigh,
                                   phaseMie, sunVisibility, extinction);
    vec3 stepTransmittance = exp(-extinction * dt);
    radiance += transmittance * source * (1.0 - stepTransmittance) / max(extinction, vec3(1e-12));
    transmittance *= stepTransmittance;
}

// The ray's extent inside the atmosphere, up to the planet (start, end); end <= start
// when it misses the atmosphere.
vec2 atmosphereSegment(vec3 origin, vec3 direction) {
    vec2 shell = raySphere(origin, direction, uTopRadius);
    if (shell.y < 0.0 || shell.x > shell.y) {
        return vec2(1.0, 0.0);
    }
    float start = max(shell.x, 0.0);
    float end = shell.y;
    vec2 planet = raySphere(origin, direction, uBottomRadius);
    if (planet.x < planet.y && planet.x > 0.0) {
        end = planet.x;
    }
    return vec2(start, end);
}

// Scattered light and transmittance along the ray up to `maxDistance` (or the planet, or
// out of the atmosphere), `steps` samples spaced quadratically: denser near the start
// (a camera in the air), or with `denseAtEnd` near the end (a ray from space down to the
// ground, where the air is densest; even steps there alias into rings around the nadir).
void integrateScatteringTo(vec3 origin, vec3 direction, vec3 sun, float maxDistance, int steps,
                           bool denseAtEnd, out vec3 radiance, out vec3 transmittance) {
    radiance = vec3(0.0);
    transmittance = vec3(1.0);
    vec2 segment = atmosphereSegment(origin, direction);
    segment.y = min(segment.y, maxDistance);
    if (segment.y <= segment.x) {
        return;
    }
    float mu = dot(direction, sun);
    float phaseRayleigh = rayleighPhase(mu);
    float phaseMie = miePhase(mu);
    float previous = segment.x;
    for (int i = 1; i <= steps; ++i) {
        float f = float(i) / float(steps);
        float spacing = denseAtEnd ? 1.0 - (1.0 - f) * (1.0 - f) : f * f;
        float t = segment.x + (segment.y - segment.x) * spacing;
        scatterSegment(origin, direction, previous, t, sun, phaseRayleigh, phaseMie, 1.0, radiance,
                       transmittance);
        previous = t;
    }
}

// The same along the whole ray, denser near the start.
void integrateScattering(vec3 origin, vec3 direction, vec3 sun, int steps, out vec3 radiance,
                         out vec3 transmittance) {
    integrateScatteringTo(origin, direction, sun, 1e30, steps, false, radiance, transmittance);
}
