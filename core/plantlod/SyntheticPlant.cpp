#include "sylva/core/plantlod/SyntheticPlant.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

namespace sylva {

namespace {

constexpr float kPi = std::numbers::pi_v<float>;

glm::vec3 anyPerpendicular(const glm::vec3& d) {
    const glm::vec3 a = std::abs(d.z) < 0.9f ? glm::vec3(0, 0, 1) : glm::vec3(1, 0, 0);
    return glm::normalize(glm::cross(d, a));
}

struct Builder {
    std::mt19937 random;
    PlantModel model;
    std::vector<int> tips;  // skeleton segments ending in a twig tip
    int maximumDepth = 3;

    float uniform(float a, float b) { return std::uniform_real_distribution<float>(a, b)(random); }

    glm::vec3 bend(const glm::vec3& direction, float angle) {
        const glm::vec3 side = anyPerpendicular(direction);
        const glm::vec3 other = glm::cross(direction, side);
        const float turn = uniform(0.0f, 2.0f * kPi);
        const glm::vec3 axis = std::cos(turn) * side + std::sin(turn) * other;
        return glm::normalize(std::cos(angle) * direction + std::sin(angle) * axis);
    }

    void branch(int parent, glm::vec3 start, glm::vec3 direction, float length, float radius,
                int depth) {
        const int pieces = 3;
        int previous = parent;
        for (int i = 0; i < pieces; ++i) {
            SkeletonSegment segment;
            segment.start = start;
            segment.end = start + direction * (length / pieces);
            segment.startRadius = radius * (1.0f - 0.25f * float(i) / pieces);
            segment.endRadius = radius * (1.0f - 0.25f * float(i + 1) / pieces);
            segment.parent = previous;
            model.skeleton.push_back(segment);
            const int index = static_cast<int>(model.skeleton.size()) - 1;
            if (depth < maximumDepth && i < pieces - 1) {
                // A lateral from this joint.
                glm::vec3 lateral = bend(direction, uniform(0.6f, 1.0f));
                lateral.z = std::max(lateral.z, 0.1f);
                branch(index, segment.end, glm::normalize(lateral), length * 0.55f,
                       segment.endRadius * 0.6f, depth + 1);
            }
            previous = index;
            start = segment.end;
            direction = bend(direction, uniform(0.05f, 0.25f));
            if (depth == 0) {
                direction = glm::normalize(direction + glm::vec3(0, 0, 1.5f));
            }
        }
        if (depth < maximumDepth) {
            branch(previous, start, bend(direction, 0.4f), length * 0.6f,
                   model.skeleton[previous].endRadius * 0.8f, depth + 1);
        } else {
            tips.push_back(previous);
        }
    }
};

void addCylinder(PlantMesh& mesh, const SkeletonSegment& segment) {
    const glm::vec3 axis = segment.end - segment.start;
    if (glm::length(axis) <= 0.0f) {
        return;
    }
    const glm::vec3 d = glm::normalize(axis);
    const glm::vec3 u = anyPerpendicular(d);
    const glm::vec3 v = glm::cross(d, u);
    const int sides = 6;
    const auto base = static_cast<std::uint32_t>(mesh.positions.size());
    for (int i = 0; i < sides; ++i) {
        const float angle = 2.0f * kPi * float(i) / sides;
        const glm::vec3 n = std::cos(angle) * u + std::sin(angle) * v;
        mesh.positions.push_back(segment.start + n * segment.startRadius);
        mesh.positions.push_back(segment.end + n * segment.endRadius);
        mesh.normals.push_back(n);
        mesh.normals.push_back(n);
    }
    for (int i = 0; i < sides; ++i) {
        const std::uint32_t a = base + 2 * i;
        const std::uint32_t b = base + 2 * ((i + 1) % sides);
        mesh.indices.insert(mesh.indices.end(), {a, b, a + 1, b, b + 1, a + 1});
    }
}

// A 16×16 leaf texture: green, opaque inside an ellipse, transparent outside.
PlantTexture leafTexture() {
    PlantTexture texture;
    texture.width = 16;
    texture.height = 16;
    texture.rgba.resize(16 * 16 * 4);
    for (int y = 0; y < 16; ++y) {
        for (int x = 0; x < 16; ++x) {
            const float u = (x + 0.5f) / 8.0f - 1.0f;
            const float v = (y + 0.5f) / 8.0f - 1.0f;
            std::uint8_t* texel = &texture.rgba[(y * 16 + x) * 4];
            texel[0] = 70;
            texel[1] = static_cast<std::uint8_t>(130 + 4 * y);
            texel[2] = 50;
            texel[3] = u * u + v * v * 1.3f <= 1.0f ? 255 : 0;
        }
    }
    return texture;
}

}  // namespace

PlantModel makeSyntheticPlant(int leafCount, std::uint32_t seed) {
    Builder builder;
    builder.random.seed(seed);
    builder.model.name = "synthetic-" + std::to_string(leafCount);
    // Depth grows with the leaf count so that tips hold about 40 leaves each.
    builder.maximumDepth = std::clamp(
        static_cast<int>(std::lround(std::log(std::max(leafCount, 1) / 40.0) / std::log(3.0))), 1,
        6);
    builder.branch(-1, glm::vec3(0.0f), glm::vec3(0, 0, 1), 4.0f, 0.15f, 0);

    PlantMaterial bark;
    bark.name = "bark";
    bark.baseColor = glm::vec4(0.25f, 0.16f, 0.09f, 1.0f);
    PlantMaterial leaf;
    leaf.name = "leaf";
    leaf.baseColor = glm::vec4(1.0f);
    leaf.baseColorTexture = leafTexture();
    leaf.alphaMasked = true;
    builder.model.materials = {bark, leaf};

    PlantMesh branches;
    branches.part = PlantPart::Branch;
    branches.material = 0;
    branches.name = "branches";
    for (const SkeletonSegment& segment : builder.model.skeleton) {
        addCylinder(branches, segment);
    }

    PlantMesh leaves;
    leaves.part = PlantPart::Leaf;
    leaves.material = 1;
    leaves.name = "leaves";
    std::normal_distribution<float> offset(0.0f, 0.3f);
    const auto& tips = builder.tips;
    for (int i = 0; i < leafCount; ++i) {
        const SkeletonSegment& tip = builder.model.skeleton[tips[i % tips.size()]];
        const glm::vec3 center = tip.end + glm::vec3(offset(builder.random), offset(builder.random),
                                                     0.7f * offset(builder.random) + 0.1f);
        const glm::vec3 normal = builder.bend(glm::vec3(0, 0, 1), builder.uniform(0.0f, 1.2f));
        const glm::vec3 along = anyPerpendicular(normal);
        const glm::vec3 across = glm::cross(normal, along);
        const float halfLength = 0.06f;
        const float halfWidth = 0.04f;
        const auto base = static_cast<std::uint32_t>(leaves.positions.size());
        const glm::vec2 corners[4] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
        for (const glm::vec2& c : corners) {
            leaves.positions.push_back(center + along * (c.x * halfLength) +
                                       across * (c.y * halfWidth));
            leaves.normals.push_back(normal);
            leaves.uvs.push_back(glm::vec2(c.x * 0.5f + 0.5f, 0.5f - c.y * 0.5f));
        }
        leaves.indices.insert(leaves.indices.end(),
                              {base, base + 1, base + 2, base, base + 2, base + 3});
    }
    builder.model.meshes = {std::move(branches), std::move(leaves)};
    return std::move(builder.model);
}

}  // namespace sylva
