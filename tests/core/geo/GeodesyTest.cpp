#include "sylva/core/geo/Geodesy.h"

#include <gtest/gtest.h>

#include <numbers>

namespace sylva {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

TEST(Geodesy, DestinationThenDistanceRoundTrips) {
    for (double bearing : {0.0, 45.0, 170.0, 300.0}) {
        for (double metres : {1.7, 5000.0, 2.5e6}) {
            double latitude = 0, longitude = 0;
            Geodesy::destination(-8.01 * kDegree, -34.84 * kDegree, bearing * kDegree, metres,
                                 latitude, longitude);
            EXPECT_NEAR(Geodesy::distance(-8.01 * kDegree, -34.84 * kDegree, latitude, longitude),
                        metres, 1e-6);
        }
    }
}

TEST(Geodesy, QuarterMeridianHasItsKnownLength) {
    // Equator to pole along a meridian on WGS84: 10,001,965.729 m.
    EXPECT_NEAR(Geodesy::distance(0.0, 0.0, 90 * kDegree, 0.0), 10001965.729, 1e-3);
}

}  // namespace
}  // namespace sylva
