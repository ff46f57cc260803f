// AtmosphereModel: brute-force CPU evaluation, in double precision and without any
// look-up table, of the scattering model the shaders implement with LUTs (Hillaire
// 2020, "A Scalable and Production Ready Sky and Atmosphere Rendering Technique",
// EGSR): single Rayleigh + Mie scattering with ozone absorption, integrated along the
// view ray with exactly integrated sun transmittance, plus Hillaire's multiple-
// scattering term Psi_ms (§5.1: second-order light and the transfer factor f_ms over
// the sphere of directions, summed to infinite order as 1 / (1 - f_ms)) evaluated at
// every sample point by direct sphere integration. It is the test oracle of the GPU
// LUTs (the discretisation, parameterisation and interpolation of the transmittance,
// multiple-scattering, sky-view and aerial-perspective tables).
//
// Frame: positions in the sphere space of the shaders (ECEF with z scaled by a/b, the
// planet a sphere of parameters.bottomRadius centred at the origin), metres. Radiance
// is per unit solar illuminance at the top of the atmosphere (multiply by
// AtmosphereParameters::sunIlluminance for cd/m^2). Slow by design (a sky radiance
// costs ~0.1 s); never fails.
#pragma once

#include <functional>

#include <glm/glm.hpp>

#include "sylva/core/atmosphere/AtmosphereParameters.h"

namespace sylva {

class AtmosphereModel {
public:
    explicit AtmosphereModel(const AtmosphereParameters& parameters) : parameters_(parameters) {}

    // Extinction (per metre, RGB) at `height` metres above the bottom sphere.
    glm::dvec3 extinction(double height) const;
    // Transmittance from `position` to the top of the atmosphere along the unit
    // `direction`; 0 when the ray hits the planet.
    glm::dvec3 transmittanceToTop(const glm::dvec3& position, const glm::dvec3& direction) const;
    // Transmittance along `distance` metres of the ray (clipped to the atmosphere and the
    // planet).
    glm::dvec3 transmittance(const glm::dvec3& position, const glm::dvec3& direction,
                             double distance) const;
    // Hillaire's Psi_ms at a point for a sun direction (unit): the multiply-scattered
    // radiance per unit illuminance and unit scattering coefficient.
    glm::dvec3 multipleScattering(const glm::dvec3& position, const glm::dvec3& sun) const;
    // Radiance scattered towards `position` along the unit `direction` (single +
    // multiple scattering), up to `maxDistance` metres or the planet or the top of the
    // atmosphere, and the transmittance of that segment. No sun disc, no ground.
    struct Segment {
        glm::dvec3 radiance{0.0};
        glm::dvec3 transmittance{1.0};
    };
    Segment scattered(const glm::dvec3& position, const glm::dvec3& direction,
                      const glm::dvec3& sun, double maxDistance = 1e12) const;
    // The same with shadowed in-scattering (seed 001 §7.2): `sunVisibility(point)` is the
    // fraction of the sun seen from a sphere-space point of the ray (0 in the shadow of
    // terrain), multiplying single scattering there; multiple scattering (skylight) is
    // not shadowed, as in the shaders.
    using SunVisibility = std::function<double(const glm::dvec3& pointSphere)>;
    Segment scattered(const glm::dvec3& position, const glm::dvec3& direction,
                      const glm::dvec3& sun, double maxDistance,
                      const SunVisibility& sunVisibility) const;

    const AtmosphereParameters& parameters() const { return parameters_; }

private:
    struct Coefficients {
        glm::dvec3 rayleighScattering, mieScattering, extinction;
    };
    Coefficients coefficients(double height) const;
    // Distance along the ray to the top of the atmosphere and whether it hits the
    // planet first (then `distance` is the ground hit).
    double rayLength(const glm::dvec3& position, const glm::dvec3& direction, bool& ground) const;

    AtmosphereParameters parameters_;
};

}  // namespace sylva
