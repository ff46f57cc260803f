// Seed 000 ch. 7 (two-level impostor validity test, Eq. 7.5 and Algorithm 1) on
// Schaufler's 1995 dynamic-impostor error metric; see the header for the geometry.
#include "sylva/core/vegetation/ImpostorValidity.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "sylva/core/base/Check.h"

namespace sylva {

namespace {

constexpr double kTiny = 1e-12;

// The eight corners of the capture's box.
void boxCorners(const ImpostorCapture& capture, glm::dvec3 (&corners)[8]) {
    for (int i = 0; i < 8; ++i) {
        corners[i] = glm::dvec3((i & 1) ? capture.boxMaximum.x : capture.boxMinimum.x,
                                (i & 2) ? capture.boxMaximum.y : capture.boxMinimum.y,
                                (i & 4) ? capture.boxMaximum.z : capture.boxMinimum.z);
    }
}

// A unit vector perpendicular to unit `axis`.
glm::dvec3 anyPerpendicular(const glm::dvec3& axis) {
    const glm::dvec3 other =
        std::abs(axis.x) < 0.9 ? glm::dvec3(1.0, 0.0, 0.0) : glm::dvec3(0.0, 1.0, 0.0);
    return glm::normalize(glm::cross(axis, other));
}

// The centre and radius of the error circle of segment p q in the half-plane through
// `viewpoint` (the circle's centre on the viewpoint's side of the segment's line).
// Returns false for a segment too short to matter.
bool errorCircle(const glm::dvec3& p, const glm::dvec3& q, const glm::dvec3& viewpoint,
                 double errorAngle, glm::dvec3& centre, double& radius) {
    const glm::dvec3 along = q - p;
    const double length = glm::length(along);
    if (length < kTiny) {
        return false;
    }
    const glm::dvec3 axis = along / length;
    const glm::dvec3 middle = 0.5 * (p + q);
    const glm::dvec3 offset = viewpoint - middle;
    const glm::dvec3 radial = offset - glm::dot(offset, axis) * axis;
    const double radialLength = glm::length(radial);
    const glm::dvec3 side = radialLength > kTiny ? radial / radialLength : anyPerpendicular(axis);
    radius = length / (2.0 * std::sin(errorAngle));  // Eq. 7.5
    centre = middle + side * (radius * std::cos(errorAngle));
    return true;
}

}  // namespace

glm::dvec3 ImpostorValidity::imageOf(const ImpostorCapture& capture, const glm::dvec3& p) {
    const glm::dvec3 centre = 0.5 * (capture.boxMinimum + capture.boxMaximum);
    const glm::dvec3 toCentre = centre - capture.viewpoint;
    const double distance = glm::length(toCentre);
    if (distance < kTiny) {
        return p;
    }
    const glm::dvec3 normal = toCentre / distance;
    const glm::dvec3 ray = p - capture.viewpoint;
    const double along = glm::dot(ray, normal);
    if (along < kTiny) {
        return p;  // at or behind the capture viewpoint: no image (groups never are)
    }
    return capture.viewpoint + ray * (distance / along);
}

double ImpostorValidity::impostorError(const ImpostorCapture& capture,
                                       const glm::dvec3& viewpoint) {
    glm::dvec3 corners[8];
    boxCorners(capture, corners);
    double largest = 0.0;
    for (const glm::dvec3& p : corners) {
        const glm::dvec3 a = p - viewpoint;
        const glm::dvec3 b = imageOf(capture, p) - viewpoint;
        largest = std::max(largest, std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b)));
    }
    return largest;
}

double ImpostorValidity::segmentClearance(const glm::dvec3& p, const glm::dvec3& q,
                                          const glm::dvec3& viewpoint, double errorAngle) {
    SYLVA_CHECK(errorAngle > 0.0 && errorAngle < 0.5 * 3.141592653589793);
    glm::dvec3 centre;
    double radius = 0.0;
    if (!errorCircle(p, q, viewpoint, errorAngle, centre, radius)) {
        return std::numeric_limits<double>::infinity();
    }
    return glm::length(viewpoint - centre) - radius;
}

double ImpostorValidity::guaranteedValidRadius(const ImpostorCapture& capture,
                                               const glm::dvec3& viewpoint, double errorAngle) {
    glm::dvec3 corners[8];
    boxCorners(capture, corners);
    double radius = std::numeric_limits<double>::infinity();
    for (const glm::dvec3& p : corners) {
        radius = std::min(radius, segmentClearance(p, imageOf(capture, p), viewpoint, errorAngle));
    }
    return radius;
}

glm::dvec3 ImpostorValidity::worstMove(const ImpostorCapture& capture, const glm::dvec3& from,
                                       double errorAngle, double distance) {
    glm::dvec3 corners[8];
    boxCorners(capture, corners);
    double nearest = std::numeric_limits<double>::infinity();
    glm::dvec3 direction(0.0, 0.0, 1.0);
    for (const glm::dvec3& p : corners) {
        glm::dvec3 centre;
        double radius = 0.0;
        if (!errorCircle(p, imageOf(capture, p), from, errorAngle, centre, radius)) {
            continue;
        }
        const double clearance = glm::length(from - centre) - radius;
        if (clearance < nearest) {
            nearest = clearance;
            direction = glm::normalize(centre - from);
        }
    }
    return from + direction * distance;
}

void ImpostorValidity::recapture(ImpostorGuard& guard, const ImpostorCapture& capture) const {
    guard.capture = capture;
    guard.volumeCentre = capture.viewpoint;
    guard.volumeRadius = guaranteedValidRadius(capture, capture.viewpoint, errorAngle_);
}

ImpostorVerdict ImpostorValidity::test(ImpostorGuard& guard, const glm::dvec3& viewpoint) {
    ++counters_.tests;
    if (guard.volumeRadius > 0.0 &&
        glm::length(viewpoint - guard.volumeCentre) < guard.volumeRadius) {
        ++counters_.insideGuaranteedVolume;
        return ImpostorVerdict::InsideGuaranteedVolume;
    }
    if (impostorError(guard.capture, viewpoint) > errorAngle_) {
        ++counters_.regenerated;
        return ImpostorVerdict::Regenerate;
    }
    ++counters_.validByMetric;
    guard.volumeCentre = viewpoint;  // Update_GVV: about the current viewpoint
    guard.volumeRadius = guaranteedValidRadius(guard.capture, viewpoint, errorAngle_);
    return ImpostorVerdict::ValidByMetric;
}

}  // namespace sylva
