// PlantModel: one plant as the LoD builder and the renderers see it, whatever file it
// came from (glTF, OBJ, or the procedural generator). Seed 001 §3.2 splits a plant
// into leaves (turned into ellipsoids, §3.3) and branches (turned into lines, §3.4);
// this type keeps that split explicit.
//
// Frame: model space, metres, +Z up, the stem base at the origin. Colours: linear RGB.
// Ownership: plain values; a PlantModel owns its meshes and decoded textures.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace sylva {

// A decoded texture, RGBA8, rows from the top (glTF convention), sRGB-encoded colour
// with linear alpha. Empty (width == 0) when the material has no texture.
struct PlantTexture {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> rgba;  // width * height * 4
};

struct PlantMaterial {
    std::string name;
    glm::vec4 baseColor{1.0f};  // linear RGB, alpha
    PlantTexture baseColorTexture;
    // Leaves are alpha-tested: texel alpha * baseColor.a < alphaCutoff is discarded.
    bool alphaMasked = false;
    float alphaCutoff = 0.5f;
};

enum class PlantPart : std::uint8_t { Branch, Leaf };

// Triangles of one part and one material. Indices are triangle lists into the
// per-vertex arrays (all of equal length; uvs may be empty when untextured).
struct PlantMesh {
    PlantPart part = PlantPart::Branch;
    int material = -1;  // index into PlantModel::materials, -1 = default grey
    std::string name;   // mesh/node name from the file, for diagnostics and overrides
    std::vector<glm::vec3> positions;
    std::vector<glm::vec3> normals;
    std::vector<glm::vec2> uvs;
    std::vector<std::uint32_t> indices;
};

// One straight piece of the branch skeleton: a truncated cone from `start` to `end`.
// Segments form a forest by `parent` (-1 for roots, i.e. the trunk base); a child
// starts on its parent's axis. Seed 001 §3.4 builds the line hierarchy on this.
struct SkeletonSegment {
    glm::vec3 start{0.0f};
    glm::vec3 end{0.0f};
    float startRadius = 0.0f;  // metres
    float endRadius = 0.0f;    // metres
    int parent = -1;
};

struct PlantModel {
    std::string name;
    std::vector<PlantMaterial> materials;
    std::vector<PlantMesh> meshes;
    // From the file when it carries one (glTF extras "sylva_skeleton"), otherwise
    // reconstructed from the branch meshes by the importer.
    std::vector<SkeletonSegment> skeleton;

    // Axis-aligned bounds of all meshes, model space metres.
    glm::vec3 boundsMinimum() const;
    glm::vec3 boundsMaximum() const;
    std::size_t triangleCount(PlantPart part) const;
};

}  // namespace sylva
