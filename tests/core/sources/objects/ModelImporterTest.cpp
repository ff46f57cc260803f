// Models for the `objects` source: the Olinda turbine's parts and hub position (the
// articulation turns the rotor about its axis and keeps the hub fixed), OBJ groups and
// colours, and the located errors of bad input (missing, unknown extension, truncated,
// malformed, without triangles; objects on polygons, unknown nodes, non-numeric angles).
#include "sylva/core/sources/objects/ModelImporter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include <unistd.h>

#include "sylva/core/geo/Ellipsoid.h"
#include "sylva/core/image/ImageWriter.h"
#include "sylva/core/scheduler/TileEvaluator.h"
#include "sylva/core/sources/objects/ObjectsSource.h"
#include "sylva/core/sources/raster/ConstantSource.h"

namespace sylva {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

std::filesystem::path folder() {
    const auto path =
        std::filesystem::temp_directory_path() / ("sylva-models-" + std::to_string(::getpid()));
    std::filesystem::create_directories(path);
    return path;
}

std::filesystem::path write(const std::string& name, const std::string& text) {
    const auto path = folder() / name;
    std::ofstream(path, std::ios::binary) << text;
    return path;
}

std::filesystem::path turbineFile() {
    return std::filesystem::path(SYLVA_TEST_DATA_DIR) / "../projects/olinda/models/turbine.gltf";
}

std::string errorOf(const std::filesystem::path& file) {
    Result<std::shared_ptr<const MeshModel>> model = importModel(file);
    return model ? std::string("(no error)") : model.error().message;
}

TEST(ModelImporter, TurbineHasNamedPartsAndItsHubAtEightyMetres) {
    Result<std::shared_ptr<const MeshModel>> model = importModel(turbineFile());
    ASSERT_TRUE(model) << model.error().message;
    const MeshModel& m = *model.value();
    const int tower = m.findPart("tower"), nacelle = m.findPart("nacelle"),
              rotor = m.findPart("rotor");
    ASSERT_GE(tower, 0);
    ASSERT_GE(nacelle, 0);
    ASSERT_GE(rotor, 0);
    EXPECT_EQ(m.parts[std::size_t(rotor)].parent, nacelle);
    // The hub (rotor origin) is 80 m up and 3 m forward (+Y) in the model frame (+Z up).
    const std::vector<glm::dmat4> rest = m.partTransforms({});
    const glm::dvec3 hub(rest[std::size_t(rotor)][3]);
    EXPECT_NEAR(hub.z, 80.0, 1e-9);
    EXPECT_NEAR(hub.y, 3.0, 1e-9);
    EXPECT_NEAR(hub.x, 0.0, 1e-9);
    // Turning the rotor keeps its hub and its axis (+Y, forward); yawing the nacelle by 90°
    // swings the hub from forward (+Y) to the side.
    std::vector<float> angles(m.parts.size(), 0.0f);
    angles[std::size_t(rotor)] = float(50 * kDegree);
    const std::vector<glm::dmat4> turned = m.partTransforms(angles);
    EXPECT_NEAR(glm::length(glm::dvec3(turned[std::size_t(rotor)][3]) - hub), 0.0, 1e-9);
    const glm::dvec3 axis = glm::dmat3(turned[std::size_t(rotor)]) * glm::dvec3(0, 1, 0);
    EXPECT_NEAR(axis.y, 1.0, 1e-9);
    angles[std::size_t(nacelle)] = float(90 * kDegree);
    const glm::dvec3 yawed(m.partTransforms(angles)[std::size_t(rotor)][3]);
    EXPECT_NEAR(std::abs(yawed.x), 3.0, 1e-6);
    EXPECT_NEAR(yawed.y, 0.0, 1e-6);
    EXPECT_NEAR(yawed.z, 80.0, 1e-9);
    EXPECT_GT(m.boundsRadius, 80.0);
}

TEST(ModelImporter, ObjGroupsBecomePartsWithMaterialColours) {
    write("box.mtl", "newmtl red\nKd 1 0 0\n");
    const auto obj = write("box.obj",
                           "mtllib box.mtl\no base\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                           "usemtl red\nf 1 2 3 4\no top\nv 0 0 1\nv 1 0 1\nv 0 1 1\nf -3 -2 -1\n");
    Result<std::shared_ptr<const MeshModel>> model = importModel(obj);
    ASSERT_TRUE(model) << model.error().message;
    ASSERT_EQ(model.value()->parts.size(), 2u);
    EXPECT_EQ(model.value()->parts[0].name, "base");
    EXPECT_EQ(model.value()->parts[1].name, "top");
    EXPECT_EQ(model.value()->triangleCount(), 3u);
    EXPECT_EQ(model.value()->parts[0].geometry.vertices[0].color & 0xffffffu, 0x0000ffu);
    EXPECT_NEAR(model.value()->parts[0].geometry.vertices[0].normal.z, 1.0f, 1e-6f);
}

// OBJ textures: map_Kd images decoded once each, `vt` flipped to the glTF convention (v
// down), and a group using two textured materials split into the group and a child part.
TEST(ModelImporter, ObjTexturesAreReadAndSplitPerPart) {
    const std::vector<std::uint8_t> red = {200, 10, 20, 255, 1, 2, 3, 255};  // 2 × 1
    ASSERT_TRUE(ImageWriter::writeRgba8(folder() / "red.png", 2, 1, red));
    const std::vector<std::uint8_t> blue = {5, 6, 250, 255};  // 1 × 1
    ASSERT_TRUE(ImageWriter::writeRgba8(folder() / "blue.png", 1, 1, blue));
    write("tex.mtl", "newmtl a\nKd 1 1 1\nmap_Kd red.png\nnewmtl b\nmap_Kd -s 1 1 1 blue.png\n");
    const auto obj = write("tex.obj",
                           "mtllib tex.mtl\no sign\nv 0 0 0\nv 1 0 0\nv 1 1 0\nvt 0.25 0.75\n"
                           "vt 1 0\nusemtl a\nf 1/1 2/2 3/1\nusemtl b\nf 1/2 3/1 2/2\n"
                           "usemtl a\nf 3/1 2/1 1/1\n");
    Result<std::shared_ptr<const MeshModel>> model = importModel(obj);
    ASSERT_TRUE(model) << model.error().message;
    const MeshModel& m = *model.value();
    ASSERT_EQ(m.textures.size(), 2u);
    EXPECT_EQ(m.textures[0].width, 2);
    EXPECT_EQ(m.textures[0].pixels, red);
    EXPECT_EQ(m.textures[1].pixels, blue);
    ASSERT_EQ(m.parts.size(), 2u);
    EXPECT_EQ(m.parts[0].name, "sign");
    EXPECT_EQ(m.parts[0].texture, 0);
    EXPECT_EQ(m.parts[0].geometry.indices.size(), 6u);
    EXPECT_EQ(m.parts[1].name, "sign#1");
    EXPECT_EQ(m.parts[1].parent, 0);
    EXPECT_EQ(m.parts[1].texture, 1);
    EXPECT_EQ(m.parts[1].geometry.indices.size(), 3u);
    EXPECT_EQ(m.parts[0].geometry.vertices[0].uv, glm::vec2(0.25f, 0.25f));
    EXPECT_EQ(m.parts[0].geometry.vertices[1].uv, glm::vec2(1.0f, 1.0f));
    // A texture that cannot be read names the MTL line.
    write("broken.mtl", "newmtl a\nmap_Kd absent.png\n");
    const auto broken = write("broken.obj", "mtllib broken.mtl\nv 0 0 0\n");
    EXPECT_EQ(errorOf(broken).rfind((folder() / "broken.mtl").string() + ":2: map_Kd: ", 0), 0u)
        << errorOf(broken);
}

TEST(ModelImporter, BadFilesAreLocatedErrors) {
    EXPECT_EQ(errorOf(folder() / "absent.glb"),
              (folder() / "absent.glb").string() + ": no such model file");
    const auto fbx = write("model.fbx", "binary");
    EXPECT_EQ(errorOf(fbx), fbx.string() + ": unknown model format '.fbx' (.gltf, .glb or .obj)");
    const auto glb = write("truncated.glb", std::string("glTF\x02\0\0\0", 8));
    EXPECT_NE(errorOf(glb).find(glb.string() + ": not a readable glTF file"), std::string::npos)
        << errorOf(glb);
    // The turbine cut in half: its JSON does not end.
    std::ifstream in(turbineFile());
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const auto half = write("half.gltf", text.substr(0, text.size() / 2));
    EXPECT_NE(errorOf(half).find(half.string() + ": not a readable glTF file"), std::string::npos)
        << errorOf(half);
    const auto empty =
        write("empty.gltf", R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],)"
                            R"("nodes":[{"name":"nothing"}]})");
    EXPECT_EQ(errorOf(empty), empty.string() + ": the model has no triangles");
    const auto obj = write("bad.obj", "v 0 0 0\nv 1 0 0\nf 1 2 9\n");
    EXPECT_EQ(errorOf(obj), obj.string() + ":3: face corner '9' refers to a missing vertex");
}

struct Placed {
    Status status;
    std::shared_ptr<const MeshTile> tile;
};

Placed place(const std::string& features, ObjectsParameters parameters) {
    const auto file =
        write("sites.geojson", R"({"type":"FeatureCollection","features":[)" + features + "]}");
    FeatureSource sites("sites", file, {});
    const ConstantSource ground("ground", 50.0);
    const ObjectsSource objects("objects", &sites, &ground, std::move(parameters));
    Result<GeographicBounds> bounds = objects.bounds();
    if (!bounds) {
        return {bounds.error(), nullptr};
    }
    TileEvaluator evaluator(TileFormat{64, 2});
    const TileKey key = MeshSource::keyOf({bounds.value().west, bounds.value().south});
    Result<std::shared_ptr<const MeshTile>> tile = objects.tile(key, evaluator);
    if (!tile) {
        return {tile.error(), nullptr};
    }
    return {Status::success(), tile.value()};
}

const std::string kPoint =
    R"({"type":"Feature","id":2,"properties":{"hub":"90","angle":"x"},"geometry":)"
    R"({"type":"Point","coordinates":[20.0,10.0]}})";

TEST(ObjectsSource, PlacesTheModelScaledToTheHubHeightOnTheTerrain) {
    ObjectsParameters p;
    p.model = turbineFile();
    p.sizeAttribute = "hub";
    p.referenceHeight = 80.0;
    p.heading = 90 * kDegree;
    const Placed placed = place(kPoint, p);
    ASSERT_TRUE(placed.status) << placed.status.error().message;
    ASSERT_EQ(placed.tile->placements.size(), 1u);
    const ModelPlacement& placement = placed.tile->placements.front();
    EXPECT_NEAR(Ellipsoid::toGeodetic(placement.position).height, 50.0, 1e-6);
    const glm::dmat3 frame = Ellipsoid::localFrame(10 * kDegree, 20 * kDegree);
    // Scale 90/80; heading 90°: the model's +Y (forward) points east.
    EXPECT_NEAR(glm::dot(placement.axes[1], frame[0]), 90.0 / 80.0, 1e-9);
    EXPECT_NEAR(glm::dot(placement.axes[2], frame[2]), 90.0 / 80.0, 1e-9);
    EXPECT_EQ(placement.featureId, 2);
}

TEST(ObjectsSource, LinesGiveObjectsAtTheSpacing) {
    // A 500 m line due north: objects at 0, 50, ... 500 m (all in one tile).
    const double north = Ellipsoid::meridionalRadius(10 * kDegree) * kDegree;
    char line[256];
    std::snprintf(line, sizeof line,
                  R"({"type":"Feature","id":1,"properties":{},"geometry":{"type":"LineString",)"
                  R"("coordinates":[[20.0,10.0],[20.0,%.10f]]}})",
                  10.0 + 500.0 / north);
    ObjectsParameters p;
    p.model = turbineFile();
    p.spacing = 50.0;
    const Placed placed = place(line, p);
    ASSERT_TRUE(placed.status) << placed.status.error().message;
    EXPECT_EQ(placed.tile->placements.size(), 11u);
}

TEST(ObjectsSource, BadPlacementsAreLocatedErrors) {
    ObjectsParameters p;
    p.model = turbineFile();
    p.partAttributes = {{"rotor", "angle"}};
    Placed placed = place(kPoint, p);
    ASSERT_FALSE(placed.status);
    EXPECT_NE(placed.status.error().message.find(
                  "sites.geojson: feature 2: attribute 'angle' is not a number: 'x'"),
              std::string::npos)
        << placed.status.error().message;

    p.partAttributes = {{"propeller", "hub"}};
    placed = place(kPoint, p);
    ASSERT_FALSE(placed.status);
    EXPECT_NE(placed.status.error().message.find(
                  "turbine.gltf: no node named 'propeller' (nodes: tower, nacelle, rotor)"),
              std::string::npos)
        << placed.status.error().message;

    p.partAttributes = {};
    placed = place(R"({"type":"Feature","id":6,"properties":{},"geometry":{"type":"Polygon",)"
                   R"("coordinates":[[[20,10],[20.001,10],[20.001,10.001],[20,10]]]}})",
                   p);
    ASSERT_FALSE(placed.status);
    EXPECT_NE(placed.status.error().message.find(
                  "feature 6: objects are placed on points or along lines, not on polygons"),
              std::string::npos)
        << placed.status.error().message;

    p.model = folder() / "missing.glb";
    placed = place(kPoint, p);
    ASSERT_FALSE(placed.status);
    EXPECT_NE(
        placed.status.error().message.find(
            "objects 'objects': " + (folder() / "missing.glb").string() + ": no such model file"),
        std::string::npos)
        << placed.status.error().message;
}

}  // namespace
}  // namespace sylva
