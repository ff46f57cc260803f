#include "sylva/core/terrain/LevelVisibility.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "sylva/core/geo/Ellipsoid.h"

namespace sylva {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

TEST(LevelVisibility, HorizonAngle) {
    const double r = Ellipsoid::kMeanRadius;
    for (double h : {10.0, 1.7e3, 8e3, 8e5, 3.6e7}) {
        EXPECT_NEAR(LevelVisibility::horizonViewAngle(h, 0.0), std::acos(r / (r + h)), 1e-12) << h;
    }
    // Mountains add their own horizon angle.
    EXPECT_NEAR(LevelVisibility::horizonViewAngle(8e3, 9e3),
                std::acos(r / (r + 8e3)) + std::acos(r / (r + 9e3)), 1e-12);
    EXPECT_DOUBLE_EQ(LevelVisibility::horizonViewAngle(1e12, 1e12), std::numbers::pi / 2);
}

TEST(LevelVisibility, PixelAngle) {
    const double r = Ellipsoid::kMeanRadius;
    const double s = 1000.0 * 2.0 * std::tan(30 * kDegree) / 720;
    EXPECT_NEAR(LevelVisibility::pixelViewAngle(1000.0, 60 * kDegree, 720), s / r, 1e-18);
}

TEST(LevelVisibility, LevelsForSpaceAircraftAndWalker) {
    // Hand-computed with r = 6371008.8 m, fov 60 deg, 720 pixels, no mountains:
    //   800 km: horizon 0.47686 rad -> log2(pi/0.47686) = 2.72 -> coarsest 2;
    //           pixel 2.0138e-4 rad -> ceil(log2(pi/2.0138e-4)) - 1 = 13.
    //   8 km:   horizon 0.050087 -> 5.97 -> 5; pixel 2.0138e-6 -> 20.
    //   1.7 m:  horizon 7.3053e-4 -> 12.07 -> 12; pixel 4.2793e-10 -> 32, clamped to 24.
    const double fov = 60 * kDegree;
    const LevelRange space = LevelVisibility::visibleLevels(800e3, 800e3, 0.0, fov, 720, 24);
    EXPECT_EQ(space.coarsest, 2);
    EXPECT_EQ(space.finest, 13);
    const LevelRange aircraft = LevelVisibility::visibleLevels(8e3, 8e3, 0.0, fov, 720, 24);
    EXPECT_EQ(aircraft.coarsest, 5);
    EXPECT_EQ(aircraft.finest, 20);
    const LevelRange walker = LevelVisibility::visibleLevels(1.7, 1.7, 0.0, fov, 720, 24);
    EXPECT_EQ(walker.coarsest, 12);
    EXPECT_EQ(walker.finest, 24);
    // Mountains beyond the horizon pull the coarsest level out.
    EXPECT_LT(LevelVisibility::visibleLevels(1.7, 1.7, 9000.0, fov, 720, 24).coarsest, 12);
}

}  // namespace
}  // namespace sylva
