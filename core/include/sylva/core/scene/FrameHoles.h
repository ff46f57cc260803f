// FrameHoles: the sky pixels of a rendered frame where the ground must be — the test of
// issue 20's `frames_with_holes` (bench/ViewerBenchmark) and of the terrain tests
// (CameraUnderCoarseGround, TerrainAccuracy). CPU only: it reads a depth buffer the
// renderer read back (reversed-Z, 0 = sky, rows top to bottom, planar camera).
//
// A pixel's ray is "deep" when it passes more than kDepth metres under the ellipsoid (made
// a sphere by scaling z) at a distance beyond `minimumDistance` along it (the bench passes
// twice the near plane; the tests 0). Rays that only graze the ellipsoid are not counted:
// the terrain rings lift their vertices by their cells' sagitta (terrain.vert) so the mesh
// encloses the surface, but its heights are floats and its relief bilinear between texels,
// so a grazing ray may still pass a few metres under it. Over terrain at or above sea
// level every deep ray must meet the ground: a deep ray showing sky is a hole.
#pragma once

#include <vector>

#include "sylva/core/scene/Camera.h"

namespace sylva {

struct FrameHoles {
    static constexpr double kDepth = 50.0;  // metres under the ellipsoid

    int deepRays = 0;              // pixels whose ray passes kDepth under the ellipsoid
    int holes = 0;                 // of those, pixels showing sky (depth 0)
    int firstX = -1, firstY = -1;  // the first hole in row order; -1 when none

    // Over `depth` (width × height) of a frame rendered with `camera`.
    static FrameHoles count(const Camera& camera, const std::vector<float>& depth, int width,
                            int height, double minimumDistance = 0.0);
};

}  // namespace sylva
