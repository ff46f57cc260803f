#include "sylva/core/atmosphere/AtmosphereModel.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace sylva {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr int kTransmittanceSteps = 512;  // transmittanceToTop
constexpr int kInnerSunSteps = 64;        // sun transmittance inside the Psi_ms integral
constexpr int kSingleSteps = 512;         // single scattering along the view ray
constexpr int kSingleSunSteps = 128;      // its sun transmittance
constexpr int kMultipleSteps = 64;        // Psi_ms samples along the view ray
constexpr int kSphereDirections = 128;    // Psi_ms: directions over the sphere
constexpr int kSphereSteps = 40;          // Psi_ms: steps along each direction

double rayleighPhase(double mu) {
    return 3.0 / (16.0 * kPi) * (1.0 + mu * mu);
}

// Cornette & Shanks 1992 (as Bruneton & Neyret 2008, Hillaire 2020).
double miePhase(double g, double mu) {
    const double g2 = g * g;
    return 3.0 / (8.0 * kPi) * (1.0 - g2) * (1.0 + mu * mu) /
           ((2.0 + g2) * std::pow(1.0 + g2 - 2.0 * g * mu, 1.5));
}

// Evenly spread unit directions (Fibonacci sphere), index i of `count`.
glm::dvec3 sphereDirection(int i, int count) {
    const double z = 1.0 - (2.0 * i + 1.0) / count;
    const double radius = std::sqrt(std::max(0.0, 1.0 - z * z));
    const double phi = i * kPi * (3.0 - std::sqrt(5.0));
    return {radius * std::cos(phi), radius * std::sin(phi), z};
}

}  // namespace

AtmosphereModel::Coefficients AtmosphereModel::coefficients(double height) const {
    const AtmosphereParameters& p = parameters_;
    const double rayleigh = std::exp(-height / p.rayleighScaleHeight);
    const double mie = std::exp(-height / p.mieScaleHeight);
    const double ozone = std::max(0.0, 1.0 - std::abs(height - p.ozoneCentre) / p.ozoneHalfWidth);
    Coefficients c;
    c.rayleighScattering = p.rayleighScattering * rayleigh;
    c.mieScattering = glm::dvec3(p.mieScattering * mie);
    c.extinction =
        c.rayleighScattering + glm::dvec3(p.mieExtinction * mie) + p.ozoneAbsorption * ozone;
    return c;
}

glm::dvec3 AtmosphereModel::extinction(double height) const {
    return coefficients(height).extinction;
}

double AtmosphereModel::rayLength(const glm::dvec3& position, const glm::dvec3& direction,
                                  bool& ground) const {
    const double b = glm::dot(position, direction);
    const double c = glm::dot(position, position);
    const double bottom = b * b - (c - parameters_.bottomRadius * parameters_.bottomRadius);
    ground = false;
    if (bottom >= 0.0 && -b - std::sqrt(bottom) > 0.0) {
        ground = true;
        return -b - std::sqrt(bottom);
    }
    const double top = b * b - (c - parameters_.topRadius * parameters_.topRadius);
    return top < 0.0 ? 0.0 : std::max(0.0, -b + std::sqrt(top));
}

namespace {

// Transmittance to the top along a ray of `steps` midpoint samples; 0 if it hits the
// ground.
template <class Model>
glm::dvec3 transmittanceSteps(const Model& model, const glm::dvec3& position,
                              const glm::dvec3& direction, double length, bool ground,
                              double bottomRadius, int steps) {
    if (ground) {
        return glm::dvec3(0.0);
    }
    const double dt = length / steps;
    glm::dvec3 depth(0.0);
    for (int i = 0; i < steps; ++i) {
        const glm::dvec3 point = position + direction * ((i + 0.5) * dt);
        depth += model.extinction(glm::length(point) - bottomRadius) * dt;
    }
    return glm::exp(-depth);
}

}  // namespace

glm::dvec3 AtmosphereModel::transmittanceToTop(const glm::dvec3& position,
                                               const glm::dvec3& direction) const {
    bool ground = false;
    const double length = rayLength(position, direction, ground);
    return transmittanceSteps(*this, position, direction, length, ground, parameters_.bottomRadius,
                              kTransmittanceSteps);
}

glm::dvec3 AtmosphereModel::transmittance(const glm::dvec3& position, const glm::dvec3& direction,
                                          double distance) const {
    bool ground = false;
    const double length = std::min(rayLength(position, direction, ground), distance);
    return transmittanceSteps(*this, position, direction, length, false, parameters_.bottomRadius,
                              kTransmittanceSteps);
}

glm::dvec3 AtmosphereModel::multipleScattering(const glm::dvec3& position,
                                               const glm::dvec3& sun) const {
    glm::dvec3 secondOrder(0.0), transfer(0.0);
    for (int d = 0; d < kSphereDirections; ++d) {
        const glm::dvec3 direction = sphereDirection(d, kSphereDirections);
        bool ground = false;
        const double length = rayLength(position, direction, ground);
        const double dt = length / kSphereSteps;
        glm::dvec3 throughput(1.0), light(0.0), transferred(0.0);
        for (int i = 0; i < kSphereSteps; ++i) {
            const glm::dvec3 point = position + direction * ((i + 0.5) * dt);
            const Coefficients c = coefficients(glm::length(point) - parameters_.bottomRadius);
            const glm::dvec3 scattering = c.rayleighScattering + c.mieScattering;
            // Exact integral over the step of scattering x transmittance (Hillaire §5.3).
            const glm::dvec3 stepTransmittance = glm::exp(-c.extinction * dt);
            const glm::dvec3 integral = throughput * scattering *
                                        (glm::dvec3(1.0) - stepTransmittance) /
                                        glm::max(c.extinction, glm::dvec3(1e-30));
            bool blocked = false;
            const double sunLength = rayLength(point, sun, blocked);
            const glm::dvec3 sunTransmittance = transmittanceSteps(
                *this, point, sun, sunLength, blocked, parameters_.bottomRadius, kInnerSunSteps);
            light += integral * sunTransmittance / (4.0 * kPi);
            transferred += integral;
            throughput *= stepTransmittance;
        }
        if (ground) {
            const glm::dvec3 point = position + direction * length;
            const glm::dvec3 normal = glm::normalize(point);
            const glm::dvec3 sunTransmittance = transmittanceToTop(point, sun);
            light += throughput * sunTransmittance * std::max(glm::dot(normal, sun), 0.0) *
                     parameters_.groundAlbedo / kPi;
        }
        secondOrder += light / double(kSphereDirections);
        transfer += transferred / double(kSphereDirections);
    }
    return secondOrder / (glm::dvec3(1.0) - transfer);
}

AtmosphereModel::Segment AtmosphereModel::scattered(const glm::dvec3& position,
                                                    const glm::dvec3& direction,
                                                    const glm::dvec3& sun,
                                                    double maxDistance) const {
    return scattered(position, direction, sun, maxDistance, SunVisibility());
}

AtmosphereModel::Segment AtmosphereModel::scattered(const glm::dvec3& position,
                                                    const glm::dvec3& direction,
                                                    const glm::dvec3& sun, double maxDistance,
                                                    const SunVisibility& sunVisibility) const {
    bool ground = false;
    const double length = std::min(rayLength(position, direction, ground), maxDistance);
    const double mu = glm::dot(direction, sun);
    const double phaseRayleigh = rayleighPhase(mu);
    const double phaseMie = miePhase(parameters_.mieAsymmetry, mu);
    Segment segment;
    // Both terms integrate each step exactly for constant coefficients (Hillaire §5.3:
    // (S - S T_step) / extinction), so long steps through dense haze stay right.
    // Single scattering, with the sun's transmittance at each step's midpoint.
    const double dt = length / kSingleSteps;
    glm::dvec3 throughput(1.0);
    for (int i = 0; i < kSingleSteps; ++i) {
        const glm::dvec3 point = position + direction * ((i + 0.5) * dt);
        const Coefficients c = coefficients(glm::length(point) - parameters_.bottomRadius);
        const glm::dvec3 stepTransmittance = glm::exp(-c.extinction * dt);
        const glm::dvec3 weight = throughput * (glm::dvec3(1.0) - stepTransmittance) /
                                  glm::max(c.extinction, glm::dvec3(1e-30));
        throughput *= stepTransmittance;
        bool blocked = false;
        const double sunLength = rayLength(point, sun, blocked);
        const glm::dvec3 sunTransmittance = transmittanceSteps(
            *this, point, sun, sunLength, blocked, parameters_.bottomRadius, kSingleSunSteps);
        const double visible = sunVisibility ? sunVisibility(point) : 1.0;
        segment.radiance += weight * sunTransmittance * visible *
                            (c.rayleighScattering * phaseRayleigh + c.mieScattering * phaseMie);
    }
    segment.transmittance = throughput;
    // Multiple scattering (Hillaire eq. 10: scattering x Psi_ms), fewer samples: the term
    // is smooth along the ray.
    const double mt = length / kMultipleSteps;
    glm::dvec3 multipleThroughput(1.0);
    for (int i = 0; i < kMultipleSteps; ++i) {
        const glm::dvec3 point = position + direction * ((i + 0.5) * mt);
        const Coefficients c = coefficients(glm::length(point) - parameters_.bottomRadius);
        const glm::dvec3 stepTransmittance = glm::exp(-c.extinction * mt);
        const glm::dvec3 weight = multipleThroughput * (glm::dvec3(1.0) - stepTransmittance) /
                                  glm::max(c.extinction, glm::dvec3(1e-30));
        multipleThroughput *= stepTransmittance;
        segment.radiance +=
            weight * (c.rayleighScattering + c.mieScattering) * multipleScattering(point, sun);
    }
    return segment;
}

}  // namespace sylva
