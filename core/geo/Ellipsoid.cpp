#include "sylva/core/geo/Ellipsoid.h"

#include <cmath>

namespace sylva {

double Ellipsoid::primeVerticalRadius(double latitude) {
    const double s = std::sin(latitude);
    return kSemiMajorAxis / std::sqrt(1.0 - kEccentricitySquared * s * s);
}

double Ellipsoid::meridionalRadius(double latitude) {
    const double s = std::sin(latitude);
    const double w = std::sqrt(1.0 - kEccentricitySquared * s * s);
    return kSemiMajorAxis * (1.0 - kEccentricitySquared) / (w * w * w);
}

glm::dvec3 Ellipsoid::toEcef(const Geodetic& position) {
    const double n = primeVerticalRadius(position.latitude);
    const double cosLat = std::cos(position.latitude);
    const double sinLat = std::sin(position.latitude);
    return {(n + position.height) * cosLat * std::cos(position.longitude),
            (n + position.height) * cosLat * std::sin(position.longitude),
            (n * (1.0 - kEccentricitySquared) + position.height) * sinLat};
}

Geodetic Ellipsoid::toGeodetic(const glm::dvec3& ecef) {
    // Zhu (1993) / Heikkinen closed form, refined by one Newton step on the latitude,
    // which brings it to full double precision at every height.
    const double a = kSemiMajorAxis;
    const double b = kSemiMinorAxis;
    const double e2 = kEccentricitySquared;
    const double ep2 = (a * a - b * b) / (b * b);
    const double p = std::hypot(ecef.x, ecef.y);
    Geodetic result;
    result.longitude = std::atan2(ecef.y, ecef.x);
    if (p < 1e-9) {  // on the polar axis
        result.latitude = ecef.z >= 0 ? M_PI / 2 : -M_PI / 2;
        result.height = std::abs(ecef.z) - b;
        return result;
    }
    const double theta = std::atan2(ecef.z * a, p * b);
    const double st = std::sin(theta);
    const double ct = std::cos(theta);
    double latitude = std::atan2(ecef.z + ep2 * b * st * st * st, p - e2 * a * ct * ct * ct);
    for (int iteration = 0; iteration < 2; ++iteration) {
        const double n = primeVerticalRadius(latitude);
        const double height = p / std::cos(latitude) - n;
        latitude = std::atan2(ecef.z, p * (1.0 - e2 * n / (n + height)));
    }
    const double sinLat = std::sin(latitude);
    const double cosLat = std::cos(latitude);
    const double n = primeVerticalRadius(latitude);
    // Height along the normal, stable near the poles and the equator alike.
    result.height = p * cosLat + ecef.z * sinLat - a * a / n;
    result.latitude = latitude;
    return result;
}

glm::dvec3 Ellipsoid::surfaceNormal(double latitude, double longitude) {
    const double cosLat = std::cos(latitude);
    return {cosLat * std::cos(longitude), cosLat * std::sin(longitude), std::sin(latitude)};
}

glm::dmat3 Ellipsoid::localFrame(double latitude, double longitude) {
    const double sinLat = std::sin(latitude), cosLat = std::cos(latitude);
    const double sinLon = std::sin(longitude), cosLon = std::cos(longitude);
    const glm::dvec3 east(-sinLon, cosLon, 0.0);
    const glm::dvec3 north(-sinLat * cosLon, -sinLat * sinLon, cosLat);
    const glm::dvec3 up(cosLat * cosLon, cosLat * sinLon, sinLat);
    return glm::dmat3(east, north, up);
}

}  // namespace sylva
