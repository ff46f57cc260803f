#include "sylva/core/geo/ProjectedCoordinates.h"

#include <gtest/gtest.h>
#include <GeographicLib/UTMUPS.hpp>

#include <numbers>

namespace sylva {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

// UTM zone 25S on WGS84 (EPSG:32725) against GeographicLib's independent UTM code,
// around Olinda and across the zone.
TEST(ProjectedCoordinates, UtmMatchesGeographicLib) {
    for (double x : {200000.0, 290000.0, 500000.0, 780000.0}) {
        for (double y : {8800000.0, 9115000.0, 9990000.0}) {
            double latitude = 0, longitude = 0;
            GeographicLib::UTMUPS::Reverse(25, false, x, y, latitude, longitude);
            Result<GeodeticPoint> ours = ProjectedCoordinates::toGeodetic("EPSG:32725", x, y);
            ASSERT_TRUE(ours) << ours.error().message;
            EXPECT_NEAR(ours->latitude / kDegree, latitude, 1e-8) << x << " " << y;
            EXPECT_NEAR(ours->longitude / kDegree, longitude, 1e-8) << x << " " << y;
        }
    }
}

TEST(ProjectedCoordinates, UnknownCrsIsAnError) {
    Result<GeodeticPoint> result = ProjectedCoordinates::toGeodetic("EPSG:99999999", 1.0, 2.0);
    ASSERT_FALSE(result);
    EXPECT_EQ(result.error().message, "unknown coordinate reference system 'EPSG:99999999'");
    EXPECT_FALSE(ProjectedCoordinates::validate("not a crs"));
    EXPECT_TRUE(ProjectedCoordinates::validate("EPSG:31985"));
}

}  // namespace
}  // namespace sylva
