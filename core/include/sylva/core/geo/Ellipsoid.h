// The WGS84 ellipsoid: conversions between geodetic coordinates (latitude, longitude in
// radians, height above the ellipsoid in metres) and ECEF (earth-centred, earth-fixed,
// metres; x through lon 0 on the equator, z through the north pole), and the local
// east/north/up frame. All in double precision: only camera-relative differences
// ever reach the GPU, as floats.
#pragma once

#include <glm/glm.hpp>

namespace sylva {

struct Geodetic {
    double latitude = 0.0;   // radians, [-pi/2, pi/2]
    double longitude = 0.0;  // radians, any value (wraps)
    double height = 0.0;     // metres above the ellipsoid
};

class Ellipsoid {
public:
    static constexpr double kSemiMajorAxis = 6378137.0;                                // a, metres
    static constexpr double kFlattening = 1.0 / 298.257223563;                         // f
    static constexpr double kEccentricitySquared = kFlattening * (2.0 - kFlattening);  // e^2
    static constexpr double kSemiMinorAxis = kSemiMajorAxis * (1.0 - kFlattening);     // b
    static constexpr double kMeanRadius = 6371008.8;  // (2a + b) / 3, metres

    // Prime vertical radius of curvature N(lat), metres.
    static double primeVerticalRadius(double latitude);
    // Meridional radius of curvature M(lat), metres.
    static double meridionalRadius(double latitude);

    static glm::dvec3 toEcef(const Geodetic& position);
    // Exact inverse (Bowring/Vermeille-free closed form by Zhu's method); heights from
    // -1e5 m to beyond geostationary orbit are accurate to well below a millimetre.
    static Geodetic toGeodetic(const glm::dvec3& ecef);

    // Unit surface normal (the "up" of the local frame) at a geodetic position.
    static glm::dvec3 surfaceNormal(double latitude, double longitude);
    // Columns: east, north, up unit vectors in ECEF at (latitude, longitude).
    static glm::dmat3 localFrame(double latitude, double longitude);
};

}  // namespace sylva
