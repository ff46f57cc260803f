// ProposalReach: the distance to the nearest part of a proposal and its horizontal extent,
// against GeographicLib's geodesics (an independent implementation) for points, and
// against plane geometry for edges (the nearest point of a wall is mid-wall), bearings
// across north, and a viewpoint surrounded by the proposal.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include <GeographicLib/Geodesic.hpp>

#include "sylva/core/analysis/ProposalReach.h"

namespace sylva {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

glm::dvec3 ecef(double latitude, double longitude, double height = 0.0) {
    return Ellipsoid::toEcef({latitude * kDegree, longitude * kDegree, height});
}

// The point `east`, `north` metres from (latitude, longitude) in its tangent plane,
// `height` above the ellipsoid.
glm::dvec3 offset(double latitude, double longitude, double east, double north,
                  double height = 0.0) {
    const glm::dmat3 frame = Ellipsoid::localFrame(latitude * kDegree, longitude * kDegree);
    Geodetic foot =
        Ellipsoid::toGeodetic(ecef(latitude, longitude) + frame[0] * east + frame[1] * north);
    foot.height = height;
    return Ellipsoid::toEcef(foot);
}

// The Olinda viewpoint 1 and the five turbines of projects/olinda/data/turbines.geojson,
// at hub height: distance and bearings as GeographicLib's inverse geodesic gives them.
TEST(ProposalReach, TurbinesMatchGeographicLib) {
    const double viewpoint[2] = {-7.9668, -34.9042};
    const double turbines[5][2] = {{-7.9531009, -34.8912212},
                                   {-7.9554504, -34.8898606},
                                   {-7.9578, -34.8885},
                                   {-7.9601496, -34.8871394},
                                   {-7.9624991, -34.8857788}};
    ProposalParts parts;
    double nearest = INFINITY, farthest = 0.0, lowest = 360.0, highest = 0.0;
    for (const auto& t : turbines) {
        parts.points.push_back(ecef(t[0], t[1], 160.0));
        double s12 = 0.0, azi1 = 0.0, azi2 = 0.0;
        GeographicLib::Geodesic::WGS84().Inverse(viewpoint[0], viewpoint[1], t[0], t[1], s12, azi1,
                                                 azi2);
        nearest = std::min(nearest, s12);
        farthest = std::max(farthest, s12);
        lowest = std::min(lowest, azi1);
        highest = std::max(highest, azi1);
    }
    const std::optional<ProposalReach> reach =
        ProposalReach::measure({viewpoint[0] * kDegree, viewpoint[1] * kDegree, 12.0}, parts);
    ASSERT_TRUE(reach);
    EXPECT_NEAR(reach->nearestDistance, nearest, 0.01);
    EXPECT_NEAR(reach->farthestDistance, farthest, 0.01);
    EXPECT_NEAR(reach->leftBearing / kDegree, lowest, 1e-4);
    EXPECT_NEAR(reach->rightBearing / kDegree, highest, 1e-4);
    EXPECT_NEAR(reach->horizontalExtent / kDegree, highest - lowest, 1e-4);
    std::printf("vp1: nearest turbine %.2f m, extent %.3f deg (%.3f to %.3f)\n",
                reach->nearestDistance, reach->horizontalExtent / kDegree, lowest, highest);
}

// 20 km away (NatureScot's farthest viewpoints) the plane measure stays within 5 cm and
// 0.001° of the geodesic, at mid-latitude.
TEST(ProposalReach, FarPointsStayCloseToTheGeodesic) {
    ProposalParts parts;
    parts.points.push_back(ecef(56.2, -4.1, 300.0));
    const std::optional<ProposalReach> reach =
        ProposalReach::measure({56.05 * kDegree, -4.25 * kDegree, 50.0}, parts);
    ASSERT_TRUE(reach);
    double s12 = 0.0, azi1 = 0.0, azi2 = 0.0;
    GeographicLib::Geodesic::WGS84().Inverse(56.05, -4.25, 56.2, -4.1, s12, azi1, azi2);
    EXPECT_GT(s12, 19000.0);
    EXPECT_NEAR(reach->nearestDistance, s12, 0.05);
    EXPECT_NEAR(reach->leftBearing / kDegree, azi1, 1e-3);
    EXPECT_DOUBLE_EQ(reach->horizontalExtent, 0.0);
}

// A wall 200 m long, 50 m north: its nearest point is mid-wall (50 m, not the 111.8 m of
// its ends) and it spans 2 atan(100 / 50) = 126.87°, from 296.57° across north to 63.43°.
TEST(ProposalReach, NearestPointOfAnEdgeAndAnExtentAcrossNorth) {
    const double lat = 10.0, lon = 20.0;
    ProposalParts parts;
    parts.segments.emplace_back(offset(lat, lon, -100.0, 50.0, 30.0),
                                offset(lat, lon, 100.0, 50.0, 30.0));
    const std::optional<ProposalReach> reach =
        ProposalReach::measure({lat * kDegree, lon * kDegree, 0.0}, parts);
    ASSERT_TRUE(reach);
    const double half = std::atan2(100.0, 50.0) / kDegree;
    EXPECT_NEAR(reach->nearestDistance, 50.0, 0.01);
    EXPECT_NEAR(reach->farthestDistance, std::hypot(100.0, 50.0), 0.01);
    EXPECT_NEAR(reach->horizontalExtent / kDegree, 2.0 * half, 1e-3);
    EXPECT_NEAR(reach->leftBearing / kDegree, 360.0 - half, 1e-3);
    EXPECT_NEAR(reach->rightBearing / kDegree, half, 1e-3);
    // A turbine due south leaves two gaps of 180° - 63.43° = 116.57° either side of it:
    // the extent is the turn without one of them, 243.43°.
    parts.points.push_back(offset(lat, lon, 0.0, -500.0));
    const std::optional<ProposalReach> both =
        ProposalReach::measure({lat * kDegree, lon * kDegree, 0.0}, parts);
    ASSERT_TRUE(both);
    EXPECT_NEAR(both->horizontalExtent / kDegree, 360.0 - (180.0 - half), 1e-3);
    EXPECT_NEAR(both->nearestDistance, 50.0, 0.01);
}

// A viewpoint inside a footprint sees the proposal all round; no parts, no reach.
TEST(ProposalReach, SurroundedViewpointAndNoProposal) {
    const double lat = -40.0, lon = 175.0;
    const double corners[4][2] = {{-20, -20}, {20, -20}, {20, 20}, {-20, 20}};
    ProposalParts parts;
    for (int i = 0; i < 4; ++i) {
        parts.segments.emplace_back(
            offset(lat, lon, corners[i][0], corners[i][1]),
            offset(lat, lon, corners[(i + 1) % 4][0], corners[(i + 1) % 4][1]));
    }
    const std::optional<ProposalReach> reach =
        ProposalReach::measure({lat * kDegree, lon * kDegree, 0.0}, parts);
    ASSERT_TRUE(reach);
    EXPECT_NEAR(reach->horizontalExtent, 2.0 * std::numbers::pi, 1e-12);
    EXPECT_NEAR(reach->nearestDistance, 20.0, 0.01);
    EXPECT_FALSE(ProposalReach::measure({0.0, 0.0, 0.0}, ProposalParts{}));
}

}  // namespace
}  // namespace sylva
