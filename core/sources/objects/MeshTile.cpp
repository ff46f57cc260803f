#include "sylva/core/sources/objects/MeshTile.h"

#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace sylva {

std::size_t MeshModel::triangleCount() const {
    std::size_t count = 0;
    for (const ModelPart& part : parts) {
        count += part.geometry.indices.size() / 3;
    }
    return count;
}

int MeshModel::findPart(const std::string& name) const {
    for (std::size_t i = 0; i < parts.size(); ++i) {
        if (parts[i].name == name) {
            return int(i);
        }
    }
    return -1;
}

std::vector<glm::dmat4> MeshModel::partTransforms(const std::vector<float>& angles) const {
    std::vector<glm::dmat4> transforms(parts.size());
    for (std::size_t i = 0; i < parts.size(); ++i) {
        glm::dmat4 local = parts[i].local;
        const double angle = i < angles.size() ? double(angles[i]) : 0.0;
        if (angle != 0.0) {
            local = local * glm::rotate(glm::dmat4(1.0), angle, parts[i].axis);
        }
        transforms[i] =
            parts[i].parent >= 0 ? transforms[std::size_t(parts[i].parent)] * local : local;
    }
    return transforms;
}

}  // namespace sylva
