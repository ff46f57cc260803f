#include "sylva/core/plantlod/PlantModel.h"

#include <limits>

namespace sylva {

glm::vec3 PlantModel::boundsMinimum() const {
    glm::vec3 minimum(std::numeric_limits<float>::max());
    for (const PlantMesh& mesh : meshes) {
        for (const glm::vec3& p : mesh.positions) {
            minimum = glm::min(minimum, p);
        }
    }
    return minimum;
}

glm::vec3 PlantModel::boundsMaximum() const {
    glm::vec3 maximum(std::numeric_limits<float>::lowest());
    for (const PlantMesh& mesh : meshes) {
        for (const glm::vec3& p : mesh.positions) {
            maximum = glm::max(maximum, p);
        }
    }
    return maximum;
}

std::size_t PlantModel::triangleCount(PlantPart part) const {
    std::size_t count = 0;
    for (const PlantMesh& mesh : meshes) {
        if (mesh.part == part) {
            count += mesh.indices.size() / 3;
        }
    }
    return count;
}

}  // namespace sylva
