#include "sylva/core/plantlod/PlantImporter.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "sylva/core/image/ImageWriter.h"
#include "sylva/core/plantlod/PlantGenerator.h"
#include "sylva/core/plantlod/PlantGltfWriter.h"

namespace sylva {
namespace {

namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
    const fs::path folder =
        fs::temp_directory_path() / ("sylva-plantimport-" + std::to_string(::getpid())) / name;
    fs::remove_all(folder);
    fs::create_directories(folder);
    return folder;
}

void writeText(const fs::path& path, const std::string& text) {
    std::ofstream out(path, std::ios::binary);
    out << text;
}

PlantModel generated(const std::string& preset, std::uint64_t seed,
                     std::optional<int> leaves = std::nullopt) {
    PlantGeneratorOptions options;
    options.seed = seed;
    options.leafCount = leaves;
    return PlantGenerator::generate(PlantGenerator::preset(preset).value(), options).value();
}

// Triangles as position triples per part, in order.
std::vector<glm::vec3> corners(const PlantModel& model, PlantPart part) {
    std::vector<glm::vec3> result;
    for (const PlantMesh& mesh : model.meshes) {
        if (mesh.part == part) {
            for (std::uint32_t index : mesh.indices) {
                result.push_back(mesh.positions[index]);
            }
        }
    }
    return result;
}

void expectSameModel(const PlantModel& a, const PlantModel& b) {
    ASSERT_EQ(a.materials.size(), b.materials.size());
    for (std::size_t i = 0; i < a.materials.size(); ++i) {
        EXPECT_EQ(a.materials[i].name, b.materials[i].name);
        EXPECT_EQ(a.materials[i].baseColor, b.materials[i].baseColor);
        EXPECT_EQ(a.materials[i].alphaMasked, b.materials[i].alphaMasked);
        EXPECT_EQ(a.materials[i].alphaCutoff, b.materials[i].alphaCutoff);
        EXPECT_EQ(a.materials[i].baseColorTexture.width, b.materials[i].baseColorTexture.width);
        EXPECT_EQ(a.materials[i].baseColorTexture.rgba, b.materials[i].baseColorTexture.rgba);
    }
    ASSERT_EQ(a.meshes.size(), b.meshes.size());
    for (std::size_t i = 0; i < a.meshes.size(); ++i) {
        EXPECT_EQ(a.meshes[i].part, b.meshes[i].part);
        EXPECT_EQ(a.meshes[i].material, b.meshes[i].material);
        EXPECT_EQ(a.meshes[i].indices, b.meshes[i].indices);
        EXPECT_EQ(a.meshes[i].positions, b.meshes[i].positions);
        EXPECT_EQ(a.meshes[i].uvs, b.meshes[i].uvs);
    }
    EXPECT_EQ(corners(a, PlantPart::Leaf), corners(b, PlantPart::Leaf));
    EXPECT_EQ(corners(a, PlantPart::Branch), corners(b, PlantPart::Branch));
    ASSERT_EQ(a.skeleton.size(), b.skeleton.size());
    for (std::size_t i = 0; i < a.skeleton.size(); ++i) {
        EXPECT_EQ(a.skeleton[i].start, b.skeleton[i].start);
        EXPECT_EQ(a.skeleton[i].end, b.skeleton[i].end);
        EXPECT_EQ(a.skeleton[i].startRadius, b.skeleton[i].startRadius);
        EXPECT_EQ(a.skeleton[i].endRadius, b.skeleton[i].endRadius);
        EXPECT_EQ(a.skeleton[i].parent, b.skeleton[i].parent);
    }
}

TEST(PlantImporter, GeneratedModelRoundTripsThroughGltfAndGlb) {
    const fs::path folder = scratch("roundtrip");
    const PlantModel model = generated("birch", 4, 2000);
    for (const char* name : {"birch.gltf", "birch.glb"}) {
        const fs::path path = folder / name;
        const Status written = PlantGltfWriter::write(model, path);
        ASSERT_TRUE(written) << written.error().message;
        Result<PlantModel> imported = PlantImporter::import(path);
        ASSERT_TRUE(imported) << imported.error().message;
        expectSameModel(model, *imported);
    }
    for (const auto& entry : fs::directory_iterator(folder)) {
        EXPECT_NE(entry.path().filename().string().rfind(".sylva-", 0), 0u)
            << "temporary left: " << entry.path();
    }
}

// Distance from p to the nearest axis of a skeleton.
float distanceToSkeleton(const glm::vec3& p, const std::vector<SkeletonSegment>& skeleton,
                         std::size_t* nearest = nullptr) {
    float best = std::numeric_limits<float>::max();
    for (std::size_t i = 0; i < skeleton.size(); ++i) {
        const glm::vec3 axis = skeleton[i].end - skeleton[i].start;
        const float lengthSquared = glm::dot(axis, axis);
        const float t =
            lengthSquared > 0.0f
                ? glm::clamp(glm::dot(p - skeleton[i].start, axis) / lengthSquared, 0.0f, 1.0f)
                : 0.0f;
        const float distance = glm::length(skeleton[i].start + axis * t - p);
        if (distance < best) {
            best = distance;
            if (nearest != nullptr) {
                *nearest = i;
            }
        }
    }
    return best;
}

TEST(PlantImporter, ReconstructedSkeletonFollowsTheGeneratedOne) {
    const fs::path folder = scratch("reconstruct");
    for (const std::string& preset : PlantGenerator::presetNames()) {
        const PlantModel model = generated(preset, 9, 3000);
        const fs::path path = folder / (preset + ".glb");
        ASSERT_TRUE(PlantGltfWriter::write(model, path));
        PlantImportOptions options;
        options.useFileSkeleton = false;
        Result<PlantModel> imported = PlantImporter::import(path, options);
        ASSERT_TRUE(imported) << imported.error().message;
        const std::vector<SkeletonSegment>& skeleton = imported->skeleton;
        ASSERT_FALSE(skeleton.empty());
        // One tree: one root, parents valid, every chain ends at the root.
        int roots = 0;
        for (std::size_t i = 0; i < skeleton.size(); ++i) {
            roots += skeleton[i].parent < 0 ? 1 : 0;
            ASSERT_LT(skeleton[i].parent, int(skeleton.size()));
            int current = int(i);
            std::size_t steps = 0;
            while (skeleton[std::size_t(current)].parent >= 0 && steps++ <= skeleton.size()) {
                current = skeleton[std::size_t(current)].parent;
            }
            ASSERT_LE(steps, skeleton.size()) << "cycle at " << i;
        }
        EXPECT_EQ(roots, 1) << preset;
        // The root starts at the trunk base and is about as thick as the (flared) base.
        const float height = model.boundsMaximum().z - model.boundsMinimum().z;
        EXPECT_LT(glm::length(skeleton[0].start - model.skeleton[0].start), 0.05f)
            << preset << ": the root starts at the trunk base";
        EXPECT_NEAR(skeleton[0].startRadius, model.skeleton[0].startRadius,
                    0.25f * model.skeleton[0].startRadius)
            << preset;
        // Every reconstructed point lies near the generated axes (tolerance: the local
        // radius plus 1.5 % of the plant height; the limit is
        // set by 3-sided twigs with 5 rings, too coarse to follow their bend closely) and the
        // generated axes are covered.
        std::size_t far = 0;
        float worst = 0.0f, worstRelative = 0.0f;
        for (const SkeletonSegment& segment : skeleton) {
            for (float t : {0.0f, 0.5f, 1.0f}) {
                std::size_t nearest = 0;
                const glm::vec3 p = glm::mix(segment.start, segment.end, t);
                const float distance = distanceToSkeleton(p, model.skeleton, &nearest);
                const float radius = std::max(model.skeleton[nearest].startRadius,
                                              model.skeleton[nearest].endRadius);
                far += distance > radius + 0.015f * height ? 1 : 0;
                worst = std::max(worst, distance);
                worstRelative = std::max(worstRelative, distance / std::max(radius, 1e-3f));
            }
        }
        EXPECT_EQ(far, 0u) << preset << ": reconstructed points away from the generated skeleton";
        std::printf(
            "%s: %zu generated, %zu reconstructed segments, worst distance %.3f m (%.2f radii), "
            "height %.1f m\n",
            preset.c_str(), model.skeleton.size(), skeleton.size(), double(worst),
            double(worstRelative), double(height));
        std::size_t uncovered = 0;
        for (const SkeletonSegment& segment : model.skeleton) {
            const glm::vec3 middle = 0.5f * (segment.start + segment.end);
            uncovered += distanceToSkeleton(middle, skeleton) >
                                 std::max(segment.startRadius, segment.endRadius) + 0.015f * height
                             ? 1
                             : 0;
        }
        EXPECT_EQ(uncovered, 0u) << preset << ": generated segments without a reconstructed one";
    }
}

TEST(PlantImporter, NodeTransformsAndYUpAreApplied) {
    // A written model whose single root node gets a translation and a 90° turn about
    // glTF's Y (up) axis: model (x, y, z) → file (x, z, −y) → rotated → back to +Z up.
    const fs::path folder = scratch("transform");
    PlantModel model = generated("bush", 2, 500);
    nlohmann::json json = nlohmann::json::parse(*PlantGltfWriter::encode(model, false));
    for (auto& node : json["nodes"]) {
        node["translation"] = {1.0, 2.0, 3.0};
        node["rotation"] = {0.0, std::sqrt(0.5), 0.0, std::sqrt(0.5)};  // +90° about Y
    }
    const fs::path path = folder / "moved.gltf";
    writeText(path, json.dump());
    Result<PlantModel> imported = PlantImporter::import(path);
    ASSERT_TRUE(imported) << imported.error().message;
    ASSERT_EQ(imported->meshes.size(), model.meshes.size());
    for (std::size_t m = 0; m < model.meshes.size(); ++m) {
        for (std::size_t i = 0; i < model.meshes[m].positions.size(); i += 97) {
            const glm::vec3 p = model.meshes[m].positions[i];
            // File frame: f = (x, z, −y); rotation +90° about Y: (fx, fy, fz) → (fz, fy, −fx);
            // translate (1, 2, 3); back to model: (X, Y, Z) → (X, −Z, Y).
            const glm::vec3 file(p.x, p.z, -p.y);
            const glm::vec3 turned(file.z, file.y, -file.x);
            const glm::vec3 moved = turned + glm::vec3(1.0f, 2.0f, 3.0f);
            const glm::vec3 expected(moved.x, -moved.z, moved.y);
            EXPECT_NEAR(glm::length(imported->meshes[m].positions[i] - expected), 0.0f, 1e-5f);
        }
    }
}

TEST(PlantImporter, ObjWithMaterialsClassifiesLeavesByAlphaTexture) {
    const fs::path folder = scratch("obj");
    // A 4×4 texture, left half transparent: written with OpenImageIO.
    std::vector<std::uint8_t> pixels(4 * 4 * 4, 0);
    for (int y = 0; y < 4; ++y) {
        for (int x = 0; x < 4; ++x) {
            std::uint8_t* p = &pixels[std::size_t(y * 4 + x) * 4];
            p[0] = 30;
            p[1] = 140;
            p[2] = 20;
            p[3] = x < 2 ? 0 : 255;
        }
    }
    ASSERT_TRUE(ImageWriter::writeRgba8(folder / "foliage texture.png", 4, 4, pixels));
    writeText(folder / "tree.mtl",
              "newmtl wood\nKd 0.3 0.2 0.1\n\nnewmtl m2\nKd 1 1 1\nmap_Kd foliage texture.png\n");
    writeText(folder / "tree.obj",
              "# a stick and a quad\nmtllib tree.mtl\n"
              "v 0 0 0\nv 0.1 0 0\nv 0 0 0.1\nv 0 1 0\n"
              "v 1 1 1\nv 2 1 1\nv 2 2 1\nv 1 2 1\n"
              "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
              "o stick\nusemtl wood\nf 1 2 4\nf 2 3 4\nf 3 1 4\n"
              "o g1\nusemtl m2\nf 5/1 6/2 7/3 8/4\n");
    Result<PlantModel> model = PlantImporter::import(folder / "tree.obj");
    ASSERT_TRUE(model) << model.error().message;
    EXPECT_EQ(model->triangleCount(PlantPart::Branch), 3u);
    EXPECT_EQ(model->triangleCount(PlantPart::Leaf), 2u);
    ASSERT_EQ(model->materials.size(), 2u);
    EXPECT_EQ(model->materials[1].baseColorTexture.width, 4);
    EXPECT_TRUE(model->materials[1].alphaMasked);
    EXPECT_FALSE(model->materials[0].alphaMasked);
    EXPECT_EQ(model->materials[0].baseColor, glm::vec4(0.3f, 0.2f, 0.1f, 1.0f));
    for (const PlantMesh& mesh : model->meshes) {
        if (mesh.part == PlantPart::Leaf) {
            // OBJ (1, 1, 1) → +Z up (1, −1, 1); vt (0, 0) → rows from the top (0, 1).
            EXPECT_EQ(mesh.positions[0], glm::vec3(1.0f, -1.0f, 1.0f));
            EXPECT_EQ(mesh.uvs[0], glm::vec2(0.0f, 1.0f));
            EXPECT_EQ(mesh.indices.size(), 6u);
            EXPECT_EQ(mesh.normals[0], glm::vec3(0.0f, -1.0f, 0.0f));  // OBJ +Z face normal → −Y
        }
    }
    // Sidecar overrides: the quad's material declared a branch, the stick a leaf.
    writeText(folder / "tree.plant.json", R"({"parts": {"m2": "branch", "stick": "leaf"}})");
    Result<PlantModel> overridden = PlantImporter::import(folder / "tree.obj");
    ASSERT_TRUE(overridden) << overridden.error().message;
    EXPECT_EQ(overridden->triangleCount(PlantPart::Branch), 2u);
    EXPECT_EQ(overridden->triangleCount(PlantPart::Leaf), 3u);
    writeText(folder / "tree.plant.json", R"({"parts": {"m2": "twig"}})");
    Result<PlantModel> bad = PlantImporter::import(folder / "tree.obj");
    ASSERT_FALSE(bad);
    EXPECT_EQ(bad.error().message,
              (folder / "tree.plant.json").string() + ": parts.m2: must be \"leaf\" or \"branch\"");
}

TEST(PlantImporter, LeafNamesClassifyOpaqueMeshes) {
    const fs::path folder = scratch("names");
    writeText(folder / "named.obj",
              "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
              "g trunk\nf 1 2 3\ng Blatt_03\nf 1 2 4\ng needles\nf 2 3 4\n");
    Result<PlantModel> model = PlantImporter::import(folder / "named.obj");
    ASSERT_TRUE(model) << model.error().message;
    EXPECT_EQ(model->triangleCount(PlantPart::Branch), 1u);
    EXPECT_EQ(model->triangleCount(PlantPart::Leaf), 2u);
}

class PlantImporterErrors : public ::testing::Test {
protected:
    void SetUp() override {
        folder = scratch("errors");
        model = generated("bush", 1, 200);
        glb = *PlantGltfWriter::encode(model, true);
        gltf = *PlantGltfWriter::encode(model, false);
    }
    std::string importError(const fs::path& path) {
        Result<PlantModel> result = PlantImporter::import(path);
        EXPECT_FALSE(result);
        return result ? "" : result.error().message;
    }
    fs::path folder;
    PlantModel model;
    std::string glb;
    std::string gltf;
};

TEST_F(PlantImporterErrors, MissingFile) {
    EXPECT_EQ(importError(folder / "none.glb"),
              (folder / "none.glb").string() + ": file not found");
}

TEST_F(PlantImporterErrors, TruncatedGlb) {
    const fs::path path = folder / "truncated.glb";
    writeText(path, glb.substr(0, 1000));
    EXPECT_EQ(importError(path), path.string() + ": truncated GLB: the header says " +
                                     std::to_string(glb.size()) + " bytes, the file has 1000");
    writeText(path, glb.substr(0, 10));
    EXPECT_EQ(importError(path),
              path.string() + ": truncated GLB: 10 bytes, less than the 20-byte header");
}

TEST_F(PlantImporterErrors, BadJson) {
    const fs::path path = folder / "bad.gltf";
    writeText(path, "{\"asset\": {\"version\": \"2.0\"}, \"nodes\": [1, 2,");
    EXPECT_EQ(importError(path), path.string() + ": corrupt glTF: invalid JSON at byte 46");
}

TEST_F(PlantImporterErrors, MissingBuffer) {
    nlohmann::json json = nlohmann::json::parse(gltf);
    json["buffers"][0]["uri"] = "missing.bin";
    const fs::path path = folder / "external.gltf";
    writeText(path, json.dump());
    EXPECT_EQ(importError(path),
              path.string() + ": buffer 0 refers to the missing file 'missing.bin'");
}

TEST_F(PlantImporterErrors, ExternalBufferAndImageLoad) {
    // The same model with its buffer and texture as files next to the .gltf.
    nlohmann::json json = nlohmann::json::parse(gltf);
    const std::string uri = json["buffers"][0]["uri"];
    const std::string prefix = "data:application/octet-stream;base64,";
    ASSERT_EQ(uri.rfind(prefix, 0), 0u);
    // Decode by round-tripping through the GLB writer's binary chunk instead of base64.
    const std::uint32_t jsonLength = *reinterpret_cast<const std::uint32_t*>(glb.data() + 12);
    const std::string binary = glb.substr(20 + jsonLength + 8);
    nlohmann::json glbJson = nlohmann::json::parse(glb.substr(20, jsonLength));
    writeText(folder / "model.bin", binary);
    glbJson["buffers"][0]["uri"] = "model.bin";
    // The image stays in its buffer view (allowed with an external buffer too).
    const fs::path path = folder / "external.gltf";
    writeText(path, glbJson.dump());
    Result<PlantModel> imported = PlantImporter::import(path);
    ASSERT_TRUE(imported) << imported.error().message;
    expectSameModel(model, *imported);
}

TEST_F(PlantImporterErrors, ExternalImageAndRootNodeSkeleton) {
    // The leaf texture as a PNG file next to the .gltf, and the skeleton moved from the
    // asset to the root node's extras.
    nlohmann::json json = nlohmann::json::parse(gltf);
    const PlantTexture& texture = model.materials[1].baseColorTexture;
    ASSERT_TRUE(
        ImageWriter::writeRgba8(folder / "leaf.png", texture.width, texture.height, texture.rgba));
    json["images"][0].erase("uri");
    json["images"][0]["uri"] = "leaf.png";
    json["nodes"][0]["extras"]["sylva_skeleton"] = json["asset"]["extras"]["sylva_skeleton"];
    json["asset"].erase("extras");
    const fs::path path = folder / "external-image.gltf";
    writeText(path, json.dump());
    Result<PlantModel> imported = PlantImporter::import(path);
    ASSERT_TRUE(imported) << imported.error().message;
    expectSameModel(model, *imported);
    json["images"][0]["uri"] = "gone.png";
    writeText(path, json.dump());
    EXPECT_EQ(importError(path), path.string() + ": image 0 refers to the missing file 'gone.png'");
}

TEST_F(PlantImporterErrors, DracoIsUnsupported) {
    nlohmann::json json = nlohmann::json::parse(gltf);
    json["extensionsUsed"] = {"KHR_draco_mesh_compression"};
    json["extensionsRequired"] = {"KHR_draco_mesh_compression"};
    const fs::path path = folder / "draco.gltf";
    writeText(path, json.dump());
    EXPECT_EQ(
        importError(path),
        path.string() +
            ": unsupported glTF feature: Draco mesh compression (KHR_draco_mesh_compression)");
}

TEST_F(PlantImporterErrors, LinesAreUnsupported) {
    nlohmann::json json = nlohmann::json::parse(gltf);
    json["meshes"][1]["primitives"][0]["mode"] = 1;
    const fs::path path = folder / "lines.gltf";
    writeText(path, json.dump());
    EXPECT_EQ(importError(path), path.string() +
                                     ": mesh 'leaves' primitive 0: unsupported glTF feature: LINES "
                                     "primitives (only triangles)");
}

TEST_F(PlantImporterErrors, ObjWithBadIndex) {
    const fs::path path = folder / "bad.obj";
    writeText(path, "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 2 9\n");
    EXPECT_EQ(importError(path),
              path.string() + ":6: face vertex index 9 out of range (4 defined)");
    writeText(path, "v 0 0 0\nv 1 0 zero\n");
    EXPECT_EQ(importError(path), path.string() + ":2: v needs three numbers");
    writeText(path, "mtllib gone.mtl\n");
    EXPECT_EQ(importError(path), path.string() + ":1: material library 'gone.mtl' not found");
}

TEST_F(PlantImporterErrors, NoLeavesOrNoBranches) {
    const fs::path path = folder / "part.obj";
    writeText(path, "v 0 0 0\nv 1 0 0\nv 0 1 0\ng trunk\nf 1 2 3\n");
    EXPECT_EQ(importError(path),
              path.string() +
                  ": the model has no leaves (no alpha-masked or alpha-textured material, no "
                  "leaf-like name, no sidecar entry)");
    writeText(path, "v 0 0 0\nv 1 0 0\nv 0 1 0\ng foliage\nf 1 2 3\n");
    EXPECT_EQ(importError(path),
              path.string() + ": the model has no branches (every mesh was classified as leaves)");
}

TEST_F(PlantImporterErrors, BadSkeletonExtras) {
    nlohmann::json json = nlohmann::json::parse(gltf);
    json["asset"]["extras"]["sylva_skeleton"][2]["parent"] = 2;
    const fs::path path = folder / "skeleton.gltf";
    writeText(path, json.dump());
    EXPECT_EQ(
        importError(path),
        path.string() +
            ": asset.extras.sylva_skeleton[2].parent: must be -1 or the index of another segment");
}

TEST_F(PlantImporterErrors, UnknownExtension) {
    const fs::path path = folder / "tree.fbx";
    writeText(path, "x");
    EXPECT_EQ(importError(path),
              path.string() + ": unsupported plant file type '.fbx' (use .gltf, .glb or .obj)");
}

}  // namespace
}  // namespace sylva
