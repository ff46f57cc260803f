#include "sylva/core/scene/Camera.h"

#include <cmath>

#include "sylva/core/model/BlockReader.h"
#include "sylva/core/model/Schema.h"

namespace sylva {
namespace {

glm::dmat3 axesFromForward(const Geodetic& at, const glm::dvec3& forward, double roll) {
    const glm::dmat3 frame = Ellipsoid::localFrame(at.latitude, at.longitude);
    const glm::dvec3 localUp = frame[2];
    glm::dvec3 right = glm::cross(forward, localUp);
    if (glm::length(right) < 1e-9) {  // looking straight up or down: keep north up
        right = glm::cross(forward, frame[1]);
    }
    right = glm::normalize(right);
    glm::dvec3 up = glm::normalize(glm::cross(right, forward));
    const double c = std::cos(roll), s = std::sin(roll);
    const glm::dvec3 rolledRight = right * c + up * s;
    const glm::dvec3 rolledUp = up * c - right * s;
    return glm::dmat3(rolledRight, rolledUp, -forward);
}

}  // namespace

glm::dmat3 Camera::axesFromAngles(const Geodetic& at, double heading, double pitch, double roll) {
    const glm::dmat3 frame = Ellipsoid::localFrame(at.latitude, at.longitude);
    const glm::dvec3 forward =
        std::cos(pitch) * (std::sin(heading) * frame[0] + std::cos(heading) * frame[1]) +
        std::sin(pitch) * frame[2];
    return axesFromForward(at, glm::normalize(forward), roll);
}

glm::dmat3 Camera::axesLookingAt(const Geodetic& from, const glm::dvec3& target) {
    const glm::dvec3 position = Ellipsoid::toEcef(from);
    return axesFromForward(from, glm::normalize(target - position), 0.0);
}

Result<Camera> Camera::fromBlock(const Block& block, const TerrainHeight& terrainHeight) {
    BlockReader reader(block, SchemaRegistry::builtin().find("camera"));
    const std::optional<GeoPosition> position = reader.geo("position");
    if (!position) {
        return Error{reader.where() + "missing 'position'"};
    }
    Camera camera;
    camera.geodetic.latitude = position->latitude;
    camera.geodetic.longitude = position->longitude;
    if (std::optional<double> eyeHeight = reader.optionalNumber("eye_height")) {
        Result<double> ground = terrainHeight(position->latitude, position->longitude);
        if (!ground) {
            return Error{reader.where("eye_height") +
                         "cannot find the terrain height: " + ground.error().message};
        }
        camera.geodetic.height = ground.value() + *eyeHeight;
    } else if (position->height) {
        camera.geodetic.height = *position->height;
    } else {
        return Error{reader.where("position") +
                     "the camera needs a height: write geo(lat, lon, height) or set eye_height"};
    }
    camera.position = Ellipsoid::toEcef(camera.geodetic);
    Result<double> fov = reader.number("fov");
    if (!fov) {
        return fov.error();
    }
    camera.verticalFov = fov.value();
    if (std::optional<GeoPosition> target = reader.geo("look_at")) {
        Geodetic t{target->latitude, target->longitude, target->height.value_or(0.0)};
        if (!target->height) {
            if (Result<double> ground = terrainHeight(t.latitude, t.longitude)) {
                t.height = std::max(ground.value(), 0.0);
            }
        }
        const glm::dvec3 targetEcef = Ellipsoid::toEcef(t);
        if (glm::length(targetEcef - camera.position) < 1e-3) {
            return Error{reader.where("look_at") + "look_at is the camera position itself"};
        }
        camera.axes = axesLookingAt(camera.geodetic, targetEcef);
    } else {
        camera.axes =
            axesFromAngles(camera.geodetic, reader.optionalNumber("heading").value_or(0.0),
                           reader.optionalNumber("pitch").value_or(0.0),
                           reader.optionalNumber("roll").value_or(0.0));
    }
    return camera;
}

}  // namespace sylva
