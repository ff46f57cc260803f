// Camera: a viewpoint in double precision. Position in ECEF metres; orientation as
// the camera's axes in ECEF (x right, y up, z backwards, as in GL view space);
// vertical field of view in radians. Built from a `camera` block of the model.
#pragma once

#include <functional>

#include <glm/glm.hpp>

#include "sylva/core/base/Result.h"
#include "sylva/core/geo/Ellipsoid.h"
#include "sylva/core/model/ProjectModel.h"

namespace sylva {

struct Camera {
    glm::dvec3 position{};     // ECEF, metres
    glm::dmat3 axes{1.0};      // columns: right, up, back, in ECEF
    double verticalFov = 1.0;  // radians
    Geodetic geodetic;         // position as latitude/longitude/height above the ellipsoid

    // ECEF -> view space rotation.
    glm::dmat3 viewRotation() const { return glm::transpose(axes); }

    // Orientation from heading (clockwise from north), pitch (up from the local
    // horizon) and roll, all radians, at the camera's position.
    static glm::dmat3 axesFromAngles(const Geodetic& at, double heading, double pitch, double roll);
    // Orientation looking from `from` to `target` (ECEF), with the local up kept up.
    static glm::dmat3 axesLookingAt(const Geodetic& from, const glm::dvec3& target);

    // Terrain height in metres at (latitude, longitude) radians, for eye_height.
    using TerrainHeight = std::function<Result<double>(double latitude, double longitude)>;
    // From a `camera` block. Errors are located at the block or attribute.
    static Result<Camera> fromBlock(const Block& block, const TerrainHeight& terrainHeight);
};

}  // namespace sylva
