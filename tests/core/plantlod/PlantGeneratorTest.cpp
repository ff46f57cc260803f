#include "sylva/core/plantlod/PlantGenerator.h"

#include <gtest/gtest.h>

#include "sylva/core/plantlod/PlantGltfWriter.h"

namespace sylva {
namespace {

PlantModel generate(const std::string& preset, std::uint64_t seed,
                    std::optional<int> leaves = std::nullopt) {
    PlantGeneratorOptions options;
    options.seed = seed;
    options.leafCount = leaves;
    Result<TreeParameters> parameters = PlantGenerator::preset(preset);
    EXPECT_TRUE(parameters) << parameters.error().message;
    Result<PlantModel> model = PlantGenerator::generate(*parameters, options);
    EXPECT_TRUE(model) << model.error().message;
    return std::move(model).value();
}

TEST(PlantGenerator, FixedSeedGivesByteIdenticalFiles) {
    for (const std::string& preset : PlantGenerator::presetNames()) {
        for (bool binary : {false, true}) {
            Result<std::string> first = PlantGltfWriter::encode(generate(preset, 7), binary);
            Result<std::string> second = PlantGltfWriter::encode(generate(preset, 7), binary);
            ASSERT_TRUE(first && second);
            EXPECT_EQ(*first, *second) << preset;
        }
    }
}

TEST(PlantGenerator, DifferentSeedsDiffer) {
    for (const std::string& preset : PlantGenerator::presetNames()) {
        const PlantModel a = generate(preset, 1);
        const PlantModel b = generate(preset, 2);
        EXPECT_NE(*PlantGltfWriter::encode(a, true), *PlantGltfWriter::encode(b, true)) << preset;
    }
}

TEST(PlantGenerator, LeafCountTargetsAreMet) {
    // The LoD benchmark needs 1k / 5k / 10k / 27k leaves within ±5 %; the generator
    // distributes them exactly (two triangles per leaf quad).
    for (const std::string& preset : PlantGenerator::presetNames()) {
        for (int target : {1000, 5000, 10000, 27000}) {
            const PlantModel model = generate(preset, 3, target);
            const double leaves = double(model.triangleCount(PlantPart::Leaf)) / 2.0;
            EXPECT_NEAR(leaves, target, 0.05 * target) << preset << " " << target;
            EXPECT_EQ(leaves, target) << preset << " " << target;
        }
    }
}

TEST(PlantGenerator, LeafSizeKeepsFoliageArea) {
    // Fewer leaves are larger (Weber & Penn's leaf quality): the total area stays.
    auto leafArea = [](const PlantModel& model) {
        double area = 0.0;
        for (const PlantMesh& mesh : model.meshes) {
            if (mesh.part != PlantPart::Leaf) {
                continue;
            }
            for (std::size_t i = 0; i < mesh.indices.size(); i += 3) {
                const glm::vec3 a = mesh.positions[mesh.indices[i]];
                area += 0.5 * glm::length(glm::cross(mesh.positions[mesh.indices[i + 1]] - a,
                                                     mesh.positions[mesh.indices[i + 2]] - a));
            }
        }
        return area;
    };
    const double few = leafArea(generate("oak", 5, 1000));
    const double many = leafArea(generate("oak", 5, 27000));
    EXPECT_NEAR(few / many, 1.0, 1e-3);
}

TEST(PlantGenerator, ModelIsConsistent) {
    for (const std::string& preset : PlantGenerator::presetNames()) {
        const PlantModel model = generate(preset, 11);
        ASSERT_EQ(model.materials.size(), 2u);
        EXPECT_FALSE(model.materials[0].alphaMasked);
        EXPECT_TRUE(model.materials[1].alphaMasked);
        EXPECT_GT(model.triangleCount(PlantPart::Branch), 100u);
        EXPECT_GT(model.triangleCount(PlantPart::Leaf), 100u);
        // The skeleton is one tree: a single root, every parent earlier in the list,
        // every child starting on its parent's axis.
        int roots = 0;
        for (std::size_t i = 0; i < model.skeleton.size(); ++i) {
            const SkeletonSegment& segment = model.skeleton[i];
            if (segment.parent < 0) {
                ++roots;
                continue;
            }
            ASSERT_LT(std::size_t(segment.parent), i);
            const SkeletonSegment& parent = model.skeleton[std::size_t(segment.parent)];
            const glm::vec3 axis = parent.end - parent.start;
            const float t = glm::clamp(
                glm::dot(segment.start - parent.start, axis) / glm::dot(axis, axis), 0.0f, 1.0f);
            EXPECT_LT(glm::length(parent.start + axis * t - segment.start), 1e-3f)
                << preset << " segment " << i;
        }
        EXPECT_EQ(roots, 1) << preset;
        // The trunk stands at the origin, up +Z.
        EXPECT_LT(glm::length(model.skeleton[0].start), 1e-6f);
        EXPECT_GT(model.boundsMaximum().z, 1.0f);
        for (const PlantMesh& mesh : model.meshes) {
            EXPECT_EQ(mesh.normals.size(), mesh.positions.size());
            EXPECT_EQ(mesh.uvs.size(), mesh.positions.size());
        }
    }
}

TEST(PlantGenerator, LeafTextureIsALeafShape) {
    const PlantTexture texture = PlantGenerator::drawLeafTexture(64, {0.1f, 0.3f, 0.05f}, false);
    ASSERT_EQ(texture.rgba.size(), 64u * 64u * 4u);
    auto alpha = [&](int x, int y) {
        return texture.rgba[(std::size_t(y) * 64 + std::size_t(x)) * 4 + 3];
    };
    EXPECT_EQ(alpha(0, 0), 0);  // corners are outside the blade
    EXPECT_EQ(alpha(63, 63), 0);
    EXPECT_EQ(alpha(0, 32), 0);     // beyond the widest margin
    EXPECT_EQ(alpha(10, 2), 0);     // beside the tip
    EXPECT_EQ(alpha(32, 30), 255);  // the middle is inside
    // Green dominates inside.
    const std::uint8_t* centre = &texture.rgba[(30 * 64 + 20) * 4];
    EXPECT_GT(centre[1], centre[0]);
    EXPECT_GT(centre[1], centre[2]);
}

TEST(PlantGenerator, UnknownPresetListsThePresets) {
    Result<TreeParameters> unknown = PlantGenerator::preset("baobab");
    ASSERT_FALSE(unknown);
    EXPECT_EQ(unknown.error().message,
              "unknown plant preset 'baobab' (presets: oak, conifer, birch, bush, palm)");
}

TEST(PlantGenerator, InvalidParametersAreReported) {
    TreeParameters tree = PlantGenerator::preset("bush").value();
    tree.levels[1].curveResolution = 0;
    Result<PlantModel> model = PlantGenerator::generate(tree, {});
    ASSERT_FALSE(model);
    EXPECT_EQ(model.error().message,
              "tree parameters 'bush': level 1: curveResolution in [1, 32], radialSegments in [3, "
              "32], branches in "
              "[0, 500], segmentSplits in [0, 2]");
}

}  // namespace
}  // namespace sylva
