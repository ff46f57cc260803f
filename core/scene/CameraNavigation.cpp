#include "sylva/core/scene/CameraNavigation.h"

#include <algorithm>
#include <cmath>

#include "sylva/core/geo/Ellipsoid.h"

namespace sylva {
namespace {

constexpr double kMaximumPitch = 89.5 * 3.14159265358979323846 / 180.0;
constexpr double kMaximumLatitude = 89.9 * 3.14159265358979323846 / 180.0;

Camera withAxes(const Camera& camera, const Geodetic& position, const glm::dmat3& axes) {
    Camera moved = camera;
    moved.geodetic = position;
    moved.position = Ellipsoid::toEcef(position);
    moved.axes = axes;
    return moved;
}

}  // namespace

CameraAngles CameraNavigation::anglesOf(const Camera& camera) {
    const glm::dmat3 frame =
        Ellipsoid::localFrame(camera.geodetic.latitude, camera.geodetic.longitude);
    const glm::dvec3 forward = -camera.axes[2];
    CameraAngles angles;
    angles.pitch = std::asin(std::clamp(glm::dot(forward, frame[2]), -1.0, 1.0));
    glm::dvec3 horizontal = forward - glm::dot(forward, frame[2]) * frame[2];
    if (glm::length(horizontal) < 1e-9) {
        horizontal = camera.axes[1];  // straight up or down: the up axis gives the heading
    }
    angles.heading = std::atan2(glm::dot(horizontal, frame[0]), glm::dot(horizontal, frame[1]));
    // axesFromAngles rolls (right, up) of the unrolled camera by the roll angle.
    const glm::dmat3 unrolled =
        Camera::axesFromAngles(camera.geodetic, angles.heading, angles.pitch, 0.0);
    angles.roll =
        std::atan2(glm::dot(camera.axes[0], unrolled[1]), glm::dot(camera.axes[0], unrolled[0]));
    return angles;
}

Camera CameraNavigation::movedTo(const Camera& camera, const Geodetic& position) {
    const CameraAngles angles = anglesOf(camera);
    return withAxes(camera, position,
                    Camera::axesFromAngles(position, angles.heading, angles.pitch, angles.roll));
}

Camera CameraNavigation::fly(const Camera& camera, double forward, double right, double up) {
    const glm::dvec3 position =
        camera.position + camera.axes[0] * right + camera.axes[1] * up - camera.axes[2] * forward;
    return movedTo(camera, Ellipsoid::toGeodetic(position));
}

Camera CameraNavigation::walk(const Camera& camera, double forward, double right) {
    const CameraAngles angles = anglesOf(camera);
    const glm::dmat3 frame =
        Ellipsoid::localFrame(camera.geodetic.latitude, camera.geodetic.longitude);
    const glm::dvec3 ahead =
        std::sin(angles.heading) * frame[0] + std::cos(angles.heading) * frame[1];
    const glm::dvec3 side =
        std::cos(angles.heading) * frame[0] - std::sin(angles.heading) * frame[1];
    Geodetic position = Ellipsoid::toGeodetic(camera.position + ahead * forward + side * right);
    position.height = camera.geodetic.height;
    return movedTo(camera, position);
}

Camera CameraNavigation::turn(const Camera& camera, double yaw, double pitch) {
    CameraAngles angles = anglesOf(camera);
    angles.heading += yaw;
    angles.pitch = std::clamp(angles.pitch + pitch, -kMaximumPitch, kMaximumPitch);
    return withAxes(
        camera, camera.geodetic,
        Camera::axesFromAngles(camera.geodetic, angles.heading, angles.pitch, angles.roll));
}

Camera CameraNavigation::orbit(const Camera& camera, double north, double east) {
    Geodetic position = camera.geodetic;
    position.latitude = std::clamp(position.latitude + north, -kMaximumLatitude, kMaximumLatitude);
    position.longitude = std::remainder(position.longitude + east, 2.0 * 3.14159265358979323846);
    return movedTo(camera, position);
}

Camera CameraNavigation::atHeight(const Camera& camera, double height) {
    Camera moved = camera;
    moved.geodetic.height = height;
    moved.position = Ellipsoid::toEcef(moved.geodetic);
    return moved;
}

double CameraNavigation::speedFor(double heightAboveGround, double minimumSpeed) {
    return std::max(heightAboveGround, minimumSpeed);
}

}  // namespace sylva
