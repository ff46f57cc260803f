// CameraNavigation: angles recovered from axes agree with Camera::axesFromAngles (the
// inverse, over a grid of positions and angles); flights cover the asked distance along
// the camera's axes (ECEF distance); walking keeps the height and moves along the
// horizon; turns clamp the pitch; orbits move over the globe at constant height.
#include "sylva/core/scene/CameraNavigation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace sylva {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

Camera cameraAt(double latitude, double longitude, double height, double heading, double pitch,
                double roll) {
    Camera camera;
    camera.geodetic = {latitude * kDegree, longitude * kDegree, height};
    camera.position = Ellipsoid::toEcef(camera.geodetic);
    camera.axes =
        Camera::axesFromAngles(camera.geodetic, heading * kDegree, pitch * kDegree, roll * kDegree);
    return camera;
}

TEST(CameraNavigation, AnglesOfInvertAxesFromAngles) {
    for (double latitude : {-80.0, -33.0, 0.0, 45.0, 89.0}) {
        for (double heading : {-170.0, -90.0, 0.0, 55.0, 179.0}) {
            for (double pitch : {-89.0, -20.0, 0.0, 35.0}) {
                for (double roll : {-30.0, 0.0, 12.0}) {
                    const Camera camera = cameraAt(latitude, 120.0, 1000.0, heading, pitch, roll);
                    const CameraAngles angles = CameraNavigation::anglesOf(camera);
                    const glm::dmat3 rebuilt = Camera::axesFromAngles(
                        camera.geodetic, angles.heading, angles.pitch, angles.roll);
                    for (int axis = 0; axis < 3; ++axis) {
                        EXPECT_LT(glm::length(rebuilt[axis] - camera.axes[axis]), 1e-9)
                            << latitude << " " << heading << " " << pitch << " " << roll;
                    }
                    EXPECT_NEAR(angles.pitch, pitch * kDegree, 1e-9);
                    EXPECT_NEAR(angles.roll, roll * kDegree, 1e-9);
                }
            }
        }
    }
}

TEST(CameraNavigation, FlyMovesAlongTheCameraAxes) {
    const Camera camera = cameraAt(33.0, 2.0, 8000.0, 55.0, -20.0, 0.0);
    const Camera moved = CameraNavigation::fly(camera, 1000.0, 200.0, -50.0);
    const glm::dvec3 expected =
        camera.position - camera.axes[2] * 1000.0 + camera.axes[0] * 200.0 - camera.axes[1] * 50.0;
    EXPECT_LT(glm::length(moved.position - expected), 1e-6);
    // Heading and pitch are kept in the new local frame (within the frame's rotation over
    // ~1 km, well under 0.01°).
    const CameraAngles before = CameraNavigation::anglesOf(camera);
    const CameraAngles after = CameraNavigation::anglesOf(moved);
    EXPECT_NEAR(after.heading, before.heading, 1e-9);
    EXPECT_NEAR(after.pitch, before.pitch, 1e-9);
}

TEST(CameraNavigation, WalkKeepsTheHeightAndFollowsTheHeading) {
    const Camera camera = cameraAt(10.0, 20.0, 1933.0, 90.0, 5.0, 0.0);  // looking east
    const Camera moved = CameraNavigation::walk(camera, 100.0, 0.0);
    EXPECT_DOUBLE_EQ(moved.geodetic.height, 1933.0);
    // 100 m east at 10° N: Δlon = 100 / (N cos φ).
    const double expected =
        100.0 / ((Ellipsoid::primeVerticalRadius(10 * kDegree) + 1933.0) * std::cos(10 * kDegree));
    EXPECT_NEAR(moved.geodetic.longitude - camera.geodetic.longitude, expected, expected * 1e-3);
    EXPECT_NEAR(moved.geodetic.latitude, camera.geodetic.latitude, 1e-8);
}

TEST(CameraNavigation, TurnClampsThePitch) {
    const Camera camera = cameraAt(0.0, 0.0, 100.0, 0.0, 80.0, 0.0);
    const CameraAngles up = CameraNavigation::anglesOf(CameraNavigation::turn(camera, 0.0, 1.0));
    EXPECT_NEAR(up.pitch, 89.5 * kDegree, 1e-9);
    const CameraAngles right =
        CameraNavigation::anglesOf(CameraNavigation::turn(camera, 30 * kDegree, 0.0));
    EXPECT_NEAR(right.heading, 30 * kDegree, 1e-9);
}

TEST(CameraNavigation, OrbitKeepsHeightAndSpeedScalesWithHeight) {
    const Camera camera = cameraAt(40.0, 170.0, 800000.0, 0.0, -90.0 + 1.0, 0.0);
    const Camera moved = CameraNavigation::orbit(camera, 5 * kDegree, 20 * kDegree);
    EXPECT_NEAR(moved.geodetic.latitude, 45 * kDegree, 1e-12);
    EXPECT_NEAR(moved.geodetic.longitude, -170 * kDegree, 1e-12);  // wrapped
    EXPECT_DOUBLE_EQ(moved.geodetic.height, 800000.0);
    EXPECT_DOUBLE_EQ(CameraNavigation::speedFor(800000.0), 800000.0);
    EXPECT_DOUBLE_EQ(CameraNavigation::speedFor(0.2), 1.5);
}

}  // namespace
}  // namespace sylva
