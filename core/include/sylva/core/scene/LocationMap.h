// LocationMap: the location plan of a viewpoint sheet (LI TGN 06/19, NatureScot v2.2: "a
// location plan with the angle of view"): a top-down view of the project's own terrain
// and layers centred on the viewpoint, north up, with the viewpoint marked, its field of
// view drawn as a wedge (the two edge bearings heading ± HFOV/2 and an arc), a north
// arrow and a scale bar.
//
// The map's camera (overhead) looks straight down from above the viewpoint's ground with
// a 40° field, so the square image spans ±radius metres at the ground; the renderer draws
// it like any other camera. Everything drawn over it is placed by ImageProjection of that
// camera, so the wedge's edges are the true bearings on the rendered ground (to the
// tangent plane at the viewpoint: 0.7 m of curvature at 3 km, well under a pixel).
#pragma once

#include "sylva/core/image/Image.h"
#include "sylva/core/scene/Camera.h"

namespace sylva {

class LocationMap {
public:
    static constexpr double kFieldOfView = 40.0 * 3.14159265358979323846 / 180.0;

    // The camera of a map spanning ±radius metres (radius > 0) around `viewpoint`'s ground
    // point, `groundHeight` metres above the ellipsoid.
    static Camera overhead(const Camera& viewpoint, double groundHeight, double radius);
    // Draws the viewpoint, the wedge of horizontal field `horizontalFov` (radians) about
    // its heading out to 0.85 radius, the north arrow and a scale bar onto `map` (the
    // render of `overhead`).
    static void draw(RgbaImage& map, const Camera& overhead, const Camera& viewpoint,
                     double horizontalFov, double radius);
    // A round length for a scale bar about a third of `radius` (1, 2 or 5 × 10^n metres).
    static double scaleLength(double radius);
};

}  // namespace sylva
