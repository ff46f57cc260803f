// CameraNavigation: the moves of the interactive viewer (`sylva view`, docs/viewer.md) on a
// Camera — fly along the camera's axes, walk along the local horizon, turn, orbit over the
// globe, keep a clearance above the ground — and the speed that scales with the height
// above the terrain, so one key press covers a few metres on foot and hundreds of
// kilometres from space. Pure functions of their inputs (no terrain access: callers pass
// ground heights from the CPU elevation query), so the viewer, its scripts and the tests
// move cameras identically.
//
// Angles are radians; heading clockwise from north, pitch up from the local horizon, roll
// about the view direction, as in a `camera` block (Camera::axesFromAngles).
#pragma once

#include <glm/glm.hpp>

#include "sylva/core/scene/Camera.h"

namespace sylva {

struct CameraAngles {
    double heading = 0.0;
    double pitch = 0.0;
    double roll = 0.0;
};

class CameraNavigation {
public:
    // The heading, pitch and roll that Camera::axesFromAngles turns back into `camera`'s
    // axes (within rounding); heading is in (-pi, pi]. Looking straight up or down the
    // heading is that of the camera's up axis.
    static CameraAngles anglesOf(const Camera& camera);

    // `camera` moved to `position`, keeping heading, pitch and roll in the new local frame.
    static Camera movedTo(const Camera& camera, const Geodetic& position);

    // Flies `forward`, `right` and `up` metres along the camera's own axes.
    static Camera fly(const Camera& camera, double forward, double right, double up);
    // Walks `forward` and `right` metres along the local horizon (the heading's direction
    // and its right), keeping the height above the ellipsoid (callers then set the eye
    // height above the ground with atHeight).
    static Camera walk(const Camera& camera, double forward, double right);
    // Turns by `yaw` (to the right, about the local up) and `pitch` (up); the pitch stays
    // within ±89.5° so the horizon never flips; roll is kept.
    static Camera turn(const Camera& camera, double yaw, double pitch);
    // Moves over the globe by `north` and `east` radians of latitude and longitude at
    // constant height, keeping heading, pitch and roll (latitude stays within ±89.9°).
    static Camera orbit(const Camera& camera, double north, double east);
    // The same camera at `height` metres above the ellipsoid.
    static Camera atHeight(const Camera& camera, double height);

    // Travel speed in metres per second for a camera `heightAboveGround` metres above the
    // terrain: one height per second (so the ground crosses the view at a steady rate),
    // at least `minimumSpeed` (walking pace near the ground).
    static double speedFor(double heightAboveGround, double minimumSpeed = 1.5);
};

}  // namespace sylva
