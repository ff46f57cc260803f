// Camera: a viewpoint in double precision. Position in ECEF metres; orientation as
// the camera's axes in ECEF (x right, y up, z backwards, as in GL view space); the
// field of view in radians and the projection of the image (planar, cylindrical or
// equirectangular; ImageProjection maps pixels to directions exactly). Built from a
// `camera` block of the model: a field of view (`fov`, `horizontal_fov`) or a
// physical lens (`focal_length` on a `sensor` or named `body`), lens shift, and the
// print format (`output_size`, `dpi`) that fixes the image's pixel size.
#pragma once

#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <string>

#include <glm/glm.hpp>

#include "sylva/core/base/Result.h"
#include "sylva/core/geo/Ellipsoid.h"
#include "sylva/core/model/ProjectModel.h"

namespace sylva {

enum class CameraProjection {
    Planar,           // pinhole: straight lines stay straight (a photograph)
    Cylindrical,      // columns are bearings at equal angle steps; rows ∝ tan(elevation)
    Equirectangular,  // columns ∝ bearing (360°), rows ∝ elevation (180°)
};

const char* projectionName(CameraProjection projection);  // "planar", "cylindrical", ...

// The physical lens and sensor a camera was described with (metadata and the source of
// its field of view). Lengths in metres; focalLength 0 means the camera was given as a
// field of view instead.
struct Lens {
    double focalLength = 0.0;
    double sensorWidth = 0.0;
    double sensorHeight = 0.0;
    std::string body;  // named body ("full_frame", ...) or empty
};

// A print format: the image's size on paper (metres) and its resolution (dots per inch).
struct PrintFormat {
    double width = 0.0;
    double height = 0.0;
    double dpi = 0.0;

    bool valid() const { return width > 0 && height > 0 && dpi > 0; }
    // Pixels across and down: the printed size in inches × dpi, rounded to the nearest pixel.
    int pixelsWide() const { return int(std::lround(width / 0.0254 * dpi)); }
    int pixelsHigh() const { return int(std::lround(height / 0.0254 * dpi)); }
};

struct Camera {
    glm::dvec3 position{};     // ECEF, metres
    glm::dmat3 axes{1.0};      // columns: right, up, back, in ECEF
    double verticalFov = 1.0;  // radians: 2 atan of half the image height's tangent window
    Geodetic geodetic;         // position as latitude/longitude/height above the ellipsoid

    // Radians. > 0: the field across the image width governs (planar: the vertical
    // field then follows from the image's aspect, see fitted(); cylindrical: the
    // panorama's angle). 0: verticalFov governs (planar only).
    double horizontalFov = 0.0;
    CameraProjection projection = CameraProjection::Planar;
    // Lens shift as fractions of the image width and height: +x moves the image window
    // right, +y up (the optical axis then lands left of / below the image centre).
    // Planar: both; cylindrical: y only (moves the horizon); equirectangular: none.
    glm::dvec2 lensShift{0.0};
    Lens lens;
    PrintFormat print;
    // Metadata: metres; NaN when unknown (the camera's height was given above the ellipsoid).
    double groundHeight = std::numeric_limits<double>::quiet_NaN();
    double eyeHeight = std::numeric_limits<double>::quiet_NaN();

    // ECEF -> view space rotation.
    glm::dmat3 viewRotation() const { return glm::transpose(axes); }

    // This camera for an image of `width` × `height` pixels: verticalFov set from the
    // horizontal field and the aspect (planar with horizontalFov > 0; cylindrical: the
    // tangent window of the rows, r = width / horizontalFov px per radian;
    // equirectangular: π). Planar cameras given a vertical field are returned unchanged.
    Camera fitted(int width, int height) const;

    // View bearing (clockwise from north) and pitch (up from the local horizon) of the
    // optical axis, and roll, radians.
    double heading() const;
    double pitch() const;

    // Orientation from heading (clockwise from north), pitch (up from the local
    // horizon) and roll, all radians, at the camera's position.
    static glm::dmat3 axesFromAngles(const Geodetic& at, double heading, double pitch, double roll);
    // Orientation looking from `from` to `target` (ECEF), with the local up kept up.
    static glm::dmat3 axesLookingAt(const Geodetic& from, const glm::dvec3& target);

    // Terrain height in metres at (latitude, longitude) radians, for eye_height.
    using TerrainHeight = std::function<Result<double>(double latitude, double longitude)>;
    // From a `camera` block. Errors are located at the block or attribute: two fields of
    // view given at once, a sensor of zero size, a panorama without its horizontal field
    // or with pitch/roll (a panorama's axis is the local vertical).
    static Result<Camera> fromBlock(const Block& block, const TerrainHeight& terrainHeight);

    // Eye height above the terrain of a viewpoint whose position has no height (TGN 06/19
    // practice: about 1.5 m).
    static constexpr double kDefaultEyeHeight = 1.5;
    static constexpr double kDefaultVerticalFov = 60.0 * 3.14159265358979323846 / 180.0;
};

}  // namespace sylva
