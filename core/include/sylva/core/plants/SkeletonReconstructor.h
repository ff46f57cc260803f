// SkeletonReconstructor: a branch skeleton (SkeletonSegments forming one tree) from
// branch triangles alone, for models that carry no skeleton (seed 001 §3.3.2: the
// branch structure "can be reconstructed from the source model").
//
// Method: vertices welded by position; connected components of the triangle graph are
// the stems. Each component is fitted by cylinders: its principal (PCA) axis, split into
// equal pieces along that axis until every piece is straight (the spread of vertex
// distances to the piece's own PCA axis is small against its radius), each piece a
// truncated cone (axis through the piece's centroid, radii by a least-squares line
// of the distance to the axis over the position along it). Components are linked into a
// forest and then one tree, Prim-style: the root is the lowest, thickest component;
// repeatedly the unattached component with an end closest to an attached segment's axis
// attaches there (that end becomes its start, parent = that segment).
//
// Frame and units: those of the input (metres, +Z up). Pure function, no failure mode:
// an empty input gives an empty skeleton.
#pragma once

#include <vector>

#include "sylva/core/plants/PlantModel.h"

namespace sylva {

class SkeletonReconstructor {
public:
    // Uses the meshes with part == Branch.
    static std::vector<SkeletonSegment> reconstruct(const std::vector<PlantMesh>& meshes);
};

}  // namespace sylva
