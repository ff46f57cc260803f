// DisplacedBillboardBuilder: displacement-mapped billboard clouds (DMBBC, seed 000 ch. 5)
// on top of a billboard-cloud level (BillboardCloudBuilder, seed 003 / 000 ch. 4). Each
// billboard quad becomes a box, the quad thickened along its normal by the largest
// distance of the geometry it simplifies (at most the level's ε: the box is the convex
// hull of what the quad stands for). Per atlas texel the builder stores the "thick shell"
// of ch. 5.2: the lowest and highest height (metres along the quad normal) of the source
// triangles that project onto that texel; the renderer ray-marches the box and takes the
// first texel whose opaque atlas alpha and height interval the ray crosses, writing that
// point's depth. Flattening the heights to 0 gives the plain billboard cloud back.
//
// Frame: the PlantModel's (metres). CPU only; built at load by the vegetation renderer
// (a few ms per level, no disk cache, so no file format to version).
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "sylva/core/base/Result.h"
#include "sylva/core/plantlod/BillboardCloudBuilder.h"
#include "sylva/core/plantlod/PlantModel.h"

namespace sylva {

struct DisplacementAtlas {
    int width = 0, height = 0;  // the level's atlas size
    // Per texel, rows from the top like the atlas: (lowest, highest) height above the
    // plane of the quad owning the texel, metres. (0, 0) where no triangle projects.
    std::vector<glm::vec2> heights;
    // Per quad: the box's half thickness (largest |height| of its texels, ≥ 1 mm).
    std::vector<float> halfThickness;
};

class DisplacedBillboardBuilder {
public:
    // `level` must come from `model` (its trianglePlane indexes the model's triangles,
    // meshes in order). Fails, naming the model, when it does not.
    static Result<DisplacementAtlas> build(const PlantModel& model, const BillboardLevel& level);
};

}  // namespace sylva
