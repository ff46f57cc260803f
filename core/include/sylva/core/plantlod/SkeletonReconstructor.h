// SkeletonReconstructor: a branch skeleton (SkeletonSegments forming one tree) from
// branch triangles alone, for models that carry no skeleton (seed 001 §3.3.2: the
// branch structure "can be reconstructed from the source model").
//
// Method: vertices welded by position; connected components of the triangle graph are
// the stems. Each stem is ordered by geodesic (edge-path) distance from one end (a double
// Dijkstra sweep starting at the extreme of its principal axis, the second from the far
// end's whole boundary loop) and fitted by cylinders: split recursively at the widest
// gap of that distance near its median until every piece is straight (radial
// spread and bend small against its radius), each piece a truncated cone (axis chosen
// among the piece's principal axes and its end-to-end direction by the smallest radial
// residual; radii by a least-squares line of the distance to the axis over the position
// along it). Stems are linked into one tree, Prim-style: the root is the component
// thickest at its lower end among those reaching the lowest point; repeatedly the unattached
// component with an end closest to an attached segment's axis attaches there (that end becomes its
// start, on the parent's axis; parent = that segment).
//
// Frame and units: those of the input (metres, +Z up). Pure function, no failure mode:
// an empty input gives an empty skeleton.
#pragma once

#include <vector>

#include "sylva/core/plantlod/PlantModel.h"

namespace sylva {

class SkeletonReconstructor {
public:
    // Uses the meshes with part == Branch.
    static std::vector<SkeletonSegment> reconstruct(const std::vector<PlantMesh>& meshes);
};

}  // namespace sylva
