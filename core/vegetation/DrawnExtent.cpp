#include "DrawnExtent.h"

#include <algorithm>

namespace sylva {

float drawnExtentRadius(const PlantAsset& asset, const glm::vec3& center) {
    float radius = 0.0f;
    const auto add = [&](const glm::vec3& point, float extra) {
        radius = std::max(radius, glm::length(point - center) + extra);
    };
    for (const LodEllipsoid& e : asset.lod.ellipsoids) {
        add(e.center, std::max({e.radii.x, e.radii.y, e.radii.z}));
    }
    for (const LodLine& l : asset.lod.lines) {
        add(l.start, l.startRadius);
        add(l.end, l.endRadius);
    }
    for (const PlantMesh& mesh : asset.model.meshes) {
        for (const glm::vec3& p : mesh.positions) {
            add(p, 0.0f);
        }
    }
    for (const BillboardLevel& level : asset.lod.billboards.levels) {
        for (const BillboardQuad& quad : level.quads) {
            for (const glm::vec3& corner : quad.corners) {
                add(corner, 0.0f);
            }
        }
    }
    // Float rounding of the instance transform: a part per ten thousand.
    return radius * 1.0001f;
}

}  // namespace sylva
