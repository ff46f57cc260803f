#include "sylva/core/geo/Ellipsoid.h"

#include <gtest/gtest.h>
#include <GeographicLib/Geocentric.hpp>

#include <cmath>
#include <numbers>
#include <random>

namespace sylva {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

// Reference values from GeographicLib, an independent implementation.
TEST(Ellipsoid, ToEcefMatchesGeographicLib) {
    const GeographicLib::Geocentric& reference = GeographicLib::Geocentric::WGS84();
    std::mt19937 random(7);
    std::uniform_real_distribution<double> latitude(-90, 90), longitude(-180, 180),
        height(-500, 1e6);
    for (int i = 0; i < 2000; ++i) {
        const double lat = latitude(random), lon = longitude(random), h = height(random);
        double x, y, z;
        reference.Forward(lat, lon, h, x, y, z);
        const glm::dvec3 ours = Ellipsoid::toEcef({lat * kDegree, lon * kDegree, h});
        EXPECT_NEAR(ours.x, x, 1e-6);
        EXPECT_NEAR(ours.y, y, 1e-6);
        EXPECT_NEAR(ours.z, z, 1e-6);
    }
}

TEST(Ellipsoid, ToGeodeticRoundTripsIncludingPolesAndAntimeridian) {
    const GeographicLib::Geocentric& reference = GeographicLib::Geocentric::WGS84();
    std::mt19937 random(11);
    std::uniform_real_distribution<double> latitude(-90, 90), longitude(-180, 180),
        height(-1e4, 4e7);
    std::vector<std::array<double, 3>> points = {
        {90, 0, 0},           {-90, 0, 1.7}, {0, 180, 8000}, {0, -180, 0}, {89.9999, 179.9999, 1.7},
        {-45, 179.99999, 100}};
    for (int i = 0; i < 2000; ++i) {
        points.push_back({latitude(random), longitude(random), height(random)});
    }
    for (const auto& [lat, lon, h] : points) {
        double x, y, z;
        reference.Forward(lat, lon, h, x, y, z);
        const Geodetic ours = Ellipsoid::toGeodetic({x, y, z});
        EXPECT_NEAR(ours.latitude / kDegree, lat, 1e-10) << lat << " " << lon << " " << h;
        EXPECT_NEAR(ours.height, h, 1e-6) << lat << " " << lon << " " << h;
        if (std::abs(lat) < 89.99999) {
            const double dLon = std::remainder(ours.longitude / kDegree - lon, 360.0);
            EXPECT_NEAR(dLon, 0.0, 1e-9);
        }
    }
}

TEST(Ellipsoid, LocalFrameIsOrthonormalAndUpIsTheSurfaceNormal) {
    const glm::dmat3 frame = Ellipsoid::localFrame(0.7, -2.1);
    EXPECT_NEAR(glm::dot(frame[0], frame[1]), 0.0, 1e-15);
    EXPECT_NEAR(glm::dot(frame[1], frame[2]), 0.0, 1e-15);
    EXPECT_NEAR(glm::length(glm::cross(frame[0], frame[1]) - frame[2]), 0.0, 1e-15);
    // Up is perpendicular to the ellipsoid: moving along east/north stays tangent.
    const double step = 1e-7;
    const glm::dvec3 p0 = Ellipsoid::toEcef({0.7, -2.1, 0});
    const glm::dvec3 pNorth = Ellipsoid::toEcef({0.7 + step, -2.1, 0});
    EXPECT_NEAR(glm::dot(glm::normalize(pNorth - p0), frame[2]), 0.0, 1e-6);
}

}  // namespace
}  // namespace sylva
