// DrawnExtent: the radius around a point (model frame, metres) that holds everything the
// vegetation renderer may draw for one plant — every ellipsoid of every level (centre
// plus its largest radius), every line (end points plus radius), every vertex of the
// source mesh and of the billboard-cloud quads. The bounding sphere of the LoD's box does
// not always hold coarse, scale-compensated ellipsoids; occlusion culling needs a sphere
// that does (issue 21 item 2).
#pragma once

#include <glm/glm.hpp>

#include "sylva/core/plantlod/PlantAsset.h"

namespace sylva {

// Metres, model frame; 0 for an asset with nothing to draw.
float drawnExtentRadius(const PlantAsset& asset, const glm::vec3& center);

}  // namespace sylva
