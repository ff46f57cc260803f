// WalkerCollision: the viewer's walker among the proposal's meshes (issue 20: "eye height
// kept above terrain and objects"): it stands on the highest surface it can step onto and
// stops short of walls, sliding along them. Pure functions of the camera, the meshes
// (MeshCollision, front faces only) and the ground height the caller passes (the
// terrain's, from the CPU elevation query), so the viewer, its scripts and the tests walk
// alike.
//
// The body: eyes `eyeHeight` above the feet; the feet step onto any surface up to
// `stepHeight` above them (kerbs, plinths, stairs) and fall onto the highest surface below
// that; walls are felt by horizontal probes from knee (just above the step height) to eye
// height, and the body keeps `radius` from them. Heights are metres along the ellipsoid
// normal; positions ECEF.
#pragma once

#include "sylva/core/scene/Camera.h"
#include "sylva/core/sources/objects/MeshCollision.h"

namespace sylva {

struct WalkerBody {
    double eyeHeight = 1.7;   // metres above the feet
    double stepHeight = 0.5;  // metres: the highest surface climbed without a wall
    double radius = 0.3;      // metres kept from walls
};

class WalkerCollision {
public:
    // The height above the ellipsoid of the surface a walker whose feet are at
    // `feetHeight` (metres above the ellipsoid) stands on at (latitude, longitude)
    // radians: the highest mesh surface at most stepHeight above the feet, or
    // `groundHeight` (the terrain) when that is higher or no mesh is there.
    static double standingHeight(const MeshCollision& meshes, double latitude, double longitude,
                                 double feetHeight, double groundHeight, const WalkerBody& body);

    // `to` (a walk from `from`: same height, another position) moved back as far as the
    // walls need: the body stops `radius` short of the first wall its probes meet, and
    // the rest of the move slides along that wall (once; a second wall stops it). The
    // orientation is `to`'s, re-expressed at the position reached; the height is `from`'s
    // (the caller then stands the walker with standingHeight).
    static Camera step(const MeshCollision& meshes, const Camera& from, const Camera& to,
                       const WalkerBody& body);
};

}  // namespace sylva
