// The proposal drawn into the G-buffer (render/objects): heights read back through the
// rendered depth against the analytic values (a building's roof at terrain + height, a
// turbine's hub at its hub height, both within 1 cm), the roof's area seen from above
// against GeographicLib's geodesic area of the footprint (0.5 %), and the depth order with
// the terrain and with other meshes.
#include <gtest/gtest.h>

#include <GeographicLib/Geodesic.hpp>
#include <GeographicLib/PolygonArea.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include <unistd.h>

#include "SceneRenderSupport.h"
#include "sylva/core/geo/Ellipsoid.h"
#include "sylva/core/image/ImageWriter.h"
#include "sylva/core/plantlod/PlantGenerator.h"
#include "sylva/core/plantlod/PlantLodBuilder.h"
#include "sylva/core/scheduler/TileEvaluator.h"
#include "sylva/core/sources/objects/BuildingsSource.h"
#include "sylva/core/sources/objects/ObjectsSource.h"
#include "sylva/core/sources/raster/ConstantSource.h"
#include "sylva/core/sources/raster/NormalMapSource.h"
#include "sylva/render/gl/GlContext.h"
#include "sylva/render/scene/SceneRenderer.h"

namespace sylva::render {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
constexpr double kLatitude = -7.96, kLongitude = -34.90;  // degrees
constexpr double kGround = 100.0;                         // metres above the ellipsoid
constexpr int kSize = 321;  // odd: the centre pixel's ray is the view axis

double metresEast() {
    return Ellipsoid::primeVerticalRadius(kLatitude * kDegree) * std::cos(kLatitude * kDegree) *
           kDegree;
}
double metresNorth() {
    return Ellipsoid::meridionalRadius(kLatitude * kDegree) * kDegree;
}

std::filesystem::path writeGeoJson(const std::string& name, const std::string& features) {
    const auto folder =
        std::filesystem::temp_directory_path() / ("sylva-objects-" + std::to_string(::getpid()));
    std::filesystem::create_directories(folder);
    const auto path = folder / name;
    std::ofstream(path) << R"({"type":"FeatureCollection","features":[)" << features << "]}";
    return path;
}

std::string rectangle(double halfEast, double halfNorth, double east0 = 0, double north0 = 0) {
    std::string out = "[[";
    const double corners[5][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}, {-1, -1}};
    for (int i = 0; i < 5; ++i) {
        char text[96];
        std::snprintf(text, sizeof text, "%s[%.10f,%.10f]", i ? "," : "",
                      kLongitude + (east0 + corners[i][0] * halfEast) / metresEast(),
                      kLatitude + (north0 + corners[i][1] * halfNorth) / metresNorth());
        out += text;
    }
    return out + "]]";
}

// A camera `above` metres over (east, north) of the test point, looking straight down.
Camera downwards(double east, double north, double height, double fov) {
    Camera c;
    c.geodetic = {(kLatitude + north / metresNorth()) * kDegree,
                  (kLongitude + east / metresEast()) * kDegree, height};
    c.position = Ellipsoid::toEcef(c.geodetic);
    c.axes = Camera::axesFromAngles(c.geodetic, 0.0, -90 * kDegree, 0.0);
    c.verticalFov = fov;
    return c;
}

class ObjectsRender : public SceneRenderFixture {
protected:
    // Renders `meshes` over the flat ground; returns the height above the ellipsoid of the
    // surface seen through pixel (x, y), from the depth buffer.
    std::vector<float> render(const std::vector<const MeshSource*>& meshes, const Camera& camera,
                              const std::vector<const InstanceBatch*>& trees = {}) {
        TerrainLayers layers{&ground_, nullptr, &normals_, {}, meshes};
        RenderSettings settings;
        settings.instanceBatches = trees;
        settings.meshes.keptBytes = keptBytes_;
        settings.width = kSize;
        settings.height = kSize;
        settings.atmosphere = false;
        settings.ocean = false;
        settings.sunDirection = glm::normalize(camera.position);
        Result<Image> image = renderer_->render(layers, evaluator_, camera, settings);
        EXPECT_TRUE(image) << image.error().message;
        lastImage_ = image ? image.value() : Image{};
        return renderer_->depth();
    }
    double heightAt(const Camera& camera, const std::vector<float>& depth, int x, int y) const {
        const float d = depth[std::size_t(y) * kSize + std::size_t(x)];
        const double tangent = std::tan(camera.verticalFov / 2);
        const glm::dvec3 view(((x + 0.5) / kSize * 2 - 1) * tangent,
                              (1 - (y + 0.5) / kSize * 2) * tangent, -1.0);
        const double distance = renderer_->near() / double(d);  // along the view axis
        const glm::dvec3 point = camera.position + camera.axes * (view * distance);
        return Ellipsoid::toGeodetic(point).height;
    }

    const ConstantSource ground_{"ground", kGround};
    const NormalMapSource normals_{"ground.normals", &ground_, 1.0};
    TileEvaluator evaluator_{TileFormat{256, 2}};
    Image lastImage_;
    std::size_t keptBytes_ = MeshSettings{}.keptBytes;
};

TEST_F(ObjectsRender, BuildingTopIsAtTerrainPlusHeight) {
    const auto file = writeGeoJson(
        "top.geojson", R"({"type":"Feature","id":1,"properties":{"h":12.0},"geometry":{"type":)"
                       R"("Polygon","coordinates":)" +
                           rectangle(15, 15) + "}}");
    FeatureSource features("footprints", file, {});
    BuildingsParameters p;
    p.heightAttribute = "h";
    const BuildingsSource buildings("houses", &features, &ground_, p);
    const Camera camera = downwards(0, 0, kGround + 300.0, 30 * kDegree);
    const std::vector<float> depth = render({&buildings}, camera);
    ASSERT_EQ(depth.size(), std::size_t(kSize) * kSize);
    EXPECT_NEAR(heightAt(camera, depth, kSize / 2, kSize / 2), kGround + 12.0, 0.01);
    // Outside the footprint the terrain is seen (the image corner is ~80 m off).
    EXPECT_NEAR(heightAt(camera, depth, 2, 2), kGround, 0.05);
}

TEST_F(ObjectsRender, AnotherScenariosTilesStayResidentButAreNotDrawn) {
    // Issue 17: drawing one scenario dropped the other's mesh tiles, so alternating
    // scenarios (a comparison, the objects benchmark) rebuilt every tile each frame.
    const auto file =
        writeGeoJson("scenario.geojson",
                     R"({"type":"Feature","id":1,"properties":{"h":12.0},"geometry":{"type":)"
                     R"("Polygon","coordinates":)" +
                         rectangle(15, 15) + "}}");
    const auto other = writeGeoJson(
        "other.geojson", R"({"type":"Feature","id":2,"properties":{"h":30.0},"geometry":{"type":)"
                         R"("Polygon","coordinates":)" +
                             rectangle(10, 10, 60, 0) + "}}");
    FeatureSource features("footprints", file, {});
    FeatureSource otherFeatures("other", other, {});
    BuildingsParameters p;
    p.heightAttribute = "h";
    const BuildingsSource today("houses", &features, &ground_, p);
    const BuildingsSource proposed("estate", &otherFeatures, &ground_, p);
    const Camera camera = downwards(0, 0, kGround + 300.0, 30 * kDegree);
    std::vector<float> depth = render({&today}, camera);
    ASSERT_EQ(renderer_->statistics().meshes.tilesBuilt, 1u);
    EXPECT_NEAR(heightAt(camera, depth, kSize / 2, kSize / 2), kGround + 12.0, 0.01);
    // The other scenario: its building drawn, this one's not (the terrain is seen).
    depth = render({&proposed}, camera);
    EXPECT_EQ(renderer_->statistics().meshes.tilesBuilt, 1u);
    EXPECT_EQ(renderer_->statistics().meshes.residentTiles, 2u);
    EXPECT_NEAR(heightAt(camera, depth, kSize / 2, kSize / 2), kGround, 0.05);
    const double east = 60.0 / (2 * 300.0 * std::tan(15 * kDegree));  // image widths
    EXPECT_NEAR(heightAt(camera, depth, int(kSize * (0.5 + east)), kSize / 2), kGround + 30.0,
                0.01);
    // Back: nothing built again, the first building drawn, the other not.
    depth = render({&today}, camera);
    EXPECT_EQ(renderer_->statistics().meshes.tilesBuilt, 0u);
    EXPECT_NEAR(heightAt(camera, depth, kSize / 2, kSize / 2), kGround + 12.0, 0.01);
    EXPECT_NEAR(heightAt(camera, depth, int(kSize * (0.5 + east)), kSize / 2), kGround, 0.05);
    // With no room for other scenarios' geometry, switching builds again.
    keptBytes_ = 0;
    depth = render({&proposed}, camera);
    EXPECT_EQ(renderer_->statistics().meshes.residentTiles, 1u);
    depth = render({&today}, camera);
    EXPECT_EQ(renderer_->statistics().meshes.tilesBuilt, 1u);
    EXPECT_NEAR(heightAt(camera, depth, kSize / 2, kSize / 2), kGround + 12.0, 0.01);
}

TEST_F(ObjectsRender, TurbineHubIsAtHubHeight) {
    const auto file =
        writeGeoJson("turbine.geojson",
                     R"({"type":"Feature","id":3,"properties":{"hub_height":90,"rotor_angle":30},)"
                     R"("geometry":{"type":"Point","coordinates":[)" +
                         std::to_string(kLongitude) + "," + std::to_string(kLatitude) + "]}}");
    FeatureSource features("sites", file, {});
    ObjectsParameters p;
    p.model = std::filesystem::path(SYLVA_PROJECTS_DIR) / "olinda/models/turbine.gltf";
    p.sizeAttribute = "hub_height";
    p.referenceHeight = 80.0;
    p.partAttributes = {{"rotor", "rotor_angle"}};
    const ObjectsSource turbines("turbines", &features, &ground_, p);
    // The nacelle's top (hub + 1.5 m in the model, × 90/80) over its centre, 2 m behind the
    // tower axis in the model (heading 0: behind is south).
    const double scale = 90.0 / 80.0;
    const Camera camera = downwards(0, -2.0 * scale, kGround + 300.0, 10 * kDegree);
    const std::vector<float> depth = render({&turbines}, camera);
    ASSERT_EQ(depth.size(), std::size_t(kSize) * kSize);
    const double top = heightAt(camera, depth, kSize / 2, kSize / 2);
    EXPECT_NEAR(top - 1.5 * scale, kGround + 90.0, 0.01);
    EXPECT_GT(renderer_->statistics().meshes.placementsDrawn, 0u);
}

TEST_F(ObjectsRender, RoofAreaFromAboveMatchesTheGeodesicArea) {
    // A 40 m × 30 m footprint turned by 27° (edges not along the pixel grid, so the pixel
    // centres sample the outline without a systematic phase).
    std::vector<std::pair<double, double>> corners;
    const double turn = 27 * kDegree;
    for (const auto& [e, n] :
         {std::pair{-20.0, -15.0}, {20.0, -15.0}, {20.0, 15.0}, {-20.0, 15.0}}) {
        corners.emplace_back(e * std::cos(turn) - n * std::sin(turn),
                             e * std::sin(turn) + n * std::cos(turn));
    }
    std::string ring = "[[";
    for (int i = 0; i <= 4; ++i) {
        char text[96];
        std::snprintf(text, sizeof text, "%s[%.10f,%.10f]", i ? "," : "",
                      kLongitude + corners[std::size_t(i % 4)].first / metresEast(),
                      kLatitude + corners[std::size_t(i % 4)].second / metresNorth());
        ring += text;
    }
    const auto file = writeGeoJson("area.geojson",
                                   R"({"type":"Feature","id":1,"properties":{},"geometry":{"type":)"
                                   R"("Polygon","coordinates":)" +
                                       ring + "]]}}");
    FeatureSource features("footprints", file, {});
    BuildingsParameters p;
    p.height = 12.0;
    const BuildingsSource buildings("houses", &features, &ground_, p);
    const double fov = 20 * kDegree, above = 200.0;
    const Camera camera = downwards(0.37, -0.21, kGround + 12.0 + above, fov);
    const std::vector<float> depth = render({&buildings}, camera);
    ASSERT_EQ(depth.size(), std::size_t(kSize) * kSize);
    int roofPixels = 0;
    for (int y = 0; y < kSize; ++y) {
        for (int x = 0; x < kSize; ++x) {
            roofPixels += std::abs(heightAt(camera, depth, x, y) - (kGround + 12.0)) < 0.05;
        }
    }
    // A plane parallel to the image plane: every pixel covers the same square on it.
    const double pixel = above * 2 * std::tan(fov / 2) / kSize;
    const double drawn = roofPixels * pixel * pixel;
    GeographicLib::PolygonArea area(GeographicLib::Geodesic::WGS84());
    for (const auto& [e, n] : corners) {
        area.AddPoint(kLatitude + n / metresNorth(), kLongitude + e / metresEast());
    }
    double perimeter = 0, geodesic = 0;
    area.Compute(false, true, perimeter, geodesic);
    EXPECT_NEAR(geodesic, 1200.0, 0.01);
    EXPECT_NEAR(drawn, geodesic, 0.005 * geodesic) << roofPixels << " roof pixels";
}

TEST_F(ObjectsRender, NearerBuildingHidesTheOneBehindAndTerrainHidesBuried) {
    // A tall building 60 m north seen from the south at eye level behind a low one 30 m
    // north: the low one hides the lower part of the tall one.
    const auto file = writeGeoJson(
        "order.geojson",
        R"({"type":"Feature","id":1,"properties":{"h":8},"geometry":{"type":"Polygon","coordinates":)" +
            rectangle(10, 5, 0, 30) +
            R"(}},{"type":"Feature","id":2,"properties":{"h":30},"geometry":{"type":"Polygon",)"
            R"("coordinates":)" +
            rectangle(10, 5, 0, 60) + "}}");
    FeatureSource features("footprints", file, {});
    BuildingsParameters p;
    p.heightAttribute = "h";
    const BuildingsSource buildings("houses", &features, &ground_, p);
    Camera camera;
    camera.geodetic = {kLatitude * kDegree, kLongitude * kDegree, kGround + 4.0};
    camera.position = Ellipsoid::toEcef(camera.geodetic);
    camera.axes = Camera::axesFromAngles(camera.geodetic, 0.0, 0.0, 0.0);
    camera.verticalFov = 60 * kDegree;
    const std::vector<float> depth = render({&buildings}, camera);
    ASSERT_EQ(depth.size(), std::size_t(kSize) * kSize);
    // The centre ray is horizontal at 4 m: it meets the low building's south wall at 25 m.
    const float centre = depth[std::size_t(kSize / 2) * kSize + kSize / 2];
    EXPECT_NEAR(renderer_->near() / centre, 25.0, 0.01);
    // A ray rising to 16 m at 55 m (over the low roof) meets the tall one's wall at 55 m.
    const double tangent = std::tan(camera.verticalFov / 2);
    const int row = int(std::lround((1 - 12.0 / 55.0 / tangent) / 2 * kSize - 0.5));
    const double rise = (1 - (row + 0.5) / kSize * 2) * tangent;
    EXPECT_NEAR(renderer_->near() / depth[std::size_t(row) * kSize + kSize / 2], 55.0, 0.05)
        << "rise " << rise;
}

TEST_F(ObjectsRender, BuildingHidesTheTreesBehindIt) {
    // A small generated oak with a quick level of detail, 40 m north of the camera; a
    // building 40 m wide and 25 m high 20 m north, between them.
    Result<TreeParameters> preset = PlantGenerator::preset("oak");
    ASSERT_TRUE(preset);
    PlantGeneratorOptions options;
    options.seed = 3;
    options.leafCount = 300;
    options.leafTextureSize = 32;
    Result<PlantModel> model = PlantGenerator::generate(preset.value(), options);
    ASSERT_TRUE(model) << model.error().message;
    PlantLodOptions lodOptions;
    lodOptions.restarts = 1;
    lodOptions.resolution = 32;
    lodOptions.views = 2;
    lodOptions.ambientOcclusionSamples = 4;
    Result<PlantLod> lod = buildPlantLod(model.value(), lodOptions);
    ASSERT_TRUE(lod) << lod.error().message;
    auto asset = std::make_shared<PlantAsset>();
    asset->name = "oak";
    asset->model = std::move(model.value());
    asset->lod = std::move(lod.value());
    Result<std::uint32_t> species = renderer_->vegetation().addSpecies(asset);
    ASSERT_TRUE(species) << species.error().message;
    InstancePlacement tree;
    tree.latitude = (kLatitude + 40.0 / metresNorth()) * kDegree;
    tree.longitude = kLongitude * kDegree;
    tree.baseEcef = Ellipsoid::toEcef({tree.latitude, tree.longitude, kGround});
    tree.scale = 1.0f;
    tree.species = species.value();
    const InstanceBatch batch =
        LodSelector::makeBatch(tree.baseEcef, {tree}, renderer_->vegetation().speciesLods());
    const auto file = writeGeoJson(
        "screen.geojson",
        R"({"type":"Feature","id":1,"properties":{},"geometry":{"type":"Polygon","coordinates":)" +
            rectangle(20, 3, 0, 20) + "}}");
    FeatureSource features("footprints", file, {});
    BuildingsParameters p;
    p.height = 25.0;
    const BuildingsSource buildings("wall", &features, &ground_, p);
    Camera camera;
    camera.geodetic = {kLatitude * kDegree, kLongitude * kDegree, kGround + 2.0};
    camera.position = Ellipsoid::toEcef(camera.geodetic);
    camera.axes = Camera::axesFromAngles(camera.geodetic, 0.0, 5 * kDegree, 0.0);
    camera.verticalFov = 50 * kDegree;
    // Pixels showing something above the ground (not terrain) at the tree's distance.
    const auto treePixels = [&](const std::vector<float>& depth) {
        int count = 0;
        for (int y = 0; y < kSize; ++y) {
            for (int x = 0; x < kSize; ++x) {
                const float d = depth[std::size_t(y) * kSize + std::size_t(x)];
                const double distance = d > 0 ? renderer_->near() / d : 1e9;
                count += distance > 30.0 && distance < 60.0 &&
                         heightAt(camera, depth, x, y) > kGround + 0.5;
            }
        }
        return count;
    };
    const int visible = treePixels(render({}, camera, {&batch}));
    EXPECT_GT(visible, 200) << "the tree alone must show";
    EXPECT_EQ(treePixels(render({&buildings}, camera, {&batch})), 0)
        << "the building must hide the tree";
}

// The 4×4 blocks of the textured-quad test's texture: four colours in an arrangement that no
// flip, transpose or rotation keeps, so a wrong u or v orientation fails.
const std::uint8_t kQuadColors[4][3] = {{255, 0, 0}, {0, 255, 0}, {0, 0, 255}, {255, 255, 0}};
int quadTexel(int column, int row) {
    return (column * 3 + row * 5 + column * row) % 4;
}

// A 40 m square facing up, textured with the 4×4 texture: glTF (external .bin and .png) or
// OBJ (+ MTL map_Kd). In the model frame (east, north) = (−x, z) of glTF, and the texture
// coordinates are u = (20 − east) / 40, v = (north + 20) / 40 in both files (OBJ stores
// 1 − v), so block (⌊4u⌋, ⌊4v⌋) lies under every point of the square.
std::filesystem::path writeTexturedQuad(const std::string& format) {
    const auto folder = std::filesystem::temp_directory_path() /
                        ("sylva-objects-" + std::to_string(::getpid())) / ("quad-" + format);
    std::filesystem::create_directories(folder);
    std::vector<std::uint8_t> pixels;
    // 64 × 64 texels in 4 × 4 blocks of one colour: bilinear filtering blends colours only
    // within half a texel (1/32 of a block) of a block border.
    for (int row = 0; row < 64; ++row) {
        for (int column = 0; column < 64; ++column) {
            const std::uint8_t* c = kQuadColors[quadTexel(column / 16, row / 16)];
            pixels.insert(pixels.end(), {c[0], c[1], c[2], 255});
        }
    }
    EXPECT_TRUE(ImageWriter::writeRgba8(folder / "quad.png", 64, 64, pixels));
    // Corners (east, north): (20, −20), (20, 20), (−20, 20), (−20, −20), counter-clockwise
    // from above.
    const float east[4] = {20, 20, -20, -20}, north[4] = {-20, 20, 20, -20};
    if (format == "obj") {
        std::ofstream(folder / "quad.mtl") << "newmtl checker\nKd 1 1 1\nmap_Kd quad.png\n";
        std::ofstream obj(folder / "quad.obj");
        obj << "mtllib quad.mtl\no quad\nusemtl checker\n";
        for (int i = 0; i < 4; ++i) {
            obj << "v " << east[i] << " " << north[i] << " 0\n";
        }
        for (int i = 0; i < 4; ++i) {
            obj << "vt " << (20 - east[i]) / 40 << " " << 1 - (north[i] + 20) / 40 << "\n";
        }
        obj << "vn 0 0 1\nf 1/1/1 2/2/1 3/3/1\nf 1/1/1 3/3/1 4/4/1\n";
        return folder / "quad.obj";
    }
    std::vector<float> data;  // positions (glTF x = −east, y = 0, z = north), normals, uvs
    for (int i = 0; i < 4; ++i) {
        data.insert(data.end(), {-east[i], 0.0f, north[i]});
    }
    for (int i = 0; i < 4; ++i) {
        data.insert(data.end(), {0.0f, 1.0f, 0.0f});
    }
    for (int i = 0; i < 4; ++i) {
        data.insert(data.end(), {(20 - east[i]) / 40, (north[i] + 20) / 40});
    }
    const std::uint16_t indices[6] = {0, 1, 2, 0, 2, 3};
    std::ofstream bin(folder / "quad.bin", std::ios::binary);
    bin.write(reinterpret_cast<const char*>(data.data()), std::streamsize(data.size() * 4));
    bin.write(reinterpret_cast<const char*>(indices), sizeof indices);
    bin.close();
    std::ofstream(folder / "quad.gltf")
        << R"({"asset":{"version":"2.0"},"scene":0,)"
        << R"("scenes":[{"nodes":[0]}],"nodes":[{"name":"quad","mesh":0}],)"
        << R"("meshes":[{"primitives":[{"attributes":{"POSITION":0,"NORMAL":1,"TEXCOORD_0":2},)"
        << R"("indices":3,"material":0}]}],)"
        << R"("materials":[{"pbrMetallicRoughness":{"baseColorTexture":{"index":0}}}],)"
        << R"("textures":[{"source":0}],"images":[{"uri":"quad.png"}],)"
        << R"("buffers":[{"uri":"quad.bin","byteLength":140}],"bufferViews":[)"
        << R"({"buffer":0,"byteOffset":0,"byteLength":48},)"
        << R"({"buffer":0,"byteOffset":48,"byteLength":48},)"
        << R"({"buffer":0,"byteOffset":96,"byteLength":32},)"
        << R"({"buffer":0,"byteOffset":128,"byteLength":12}],"accessors":[)"
        << R"({"bufferView":0,"componentType":5126,"count":4,"type":"VEC3",)"
        << R"("min":[-20,0,-20],"max":[20,0,20]},)"
        << R"({"bufferView":1,"componentType":5126,"count":4,"type":"VEC3"},)"
        << R"({"bufferView":2,"componentType":5126,"count":4,"type":"VEC2"},)"
        << R"({"bufferView":3,"componentType":5123,"count":6,"type":"SCALAR"}]})";
    return folder / "quad.gltf";
}

// The CPU oracle: every pixel whose depth-buffer point lies on the square (1 m above the
// ground) away from texel borders must show the colour of the texel under it, told apart
// by chromaticity (the light scales the channels alike; sun overhead, no atmosphere).
TEST_F(ObjectsRender, TexturedQuadFromAboveShowsTheTexture) {
    for (const std::string format : {"gltf", "obj"}) {
        SCOPED_TRACE(format);
        const auto sites =
            writeGeoJson("quad.geojson", R"({"type":"Feature","id":1,"properties":{},"geometry":)"
                                         R"({"type":"Point","coordinates":[)" +
                                             std::to_string(kLongitude) + "," +
                                             std::to_string(kLatitude) + "]}}");
        FeatureSource features("sites", sites, {});
        ObjectsParameters p;
        p.model = writeTexturedQuad(format);
        p.height = 1.0;
        const ObjectsSource quad("quad", &features, &ground_, p);
        const Camera camera = downwards(0, 0, kGround + 120.0, 25 * kDegree);
        const std::vector<float> depth = render({&quad}, camera);
        ASSERT_EQ(depth.size(), std::size_t(kSize) * kSize);
        int checked = 0, wrong = 0;
        int seen[4] = {0, 0, 0, 0};
        for (int y = 0; y < kSize; y += 2) {
            for (int x = 0; x < kSize; x += 2) {
                if (std::abs(heightAt(camera, depth, x, y) - (kGround + 1.0)) > 0.05) {
                    continue;  // the ground around the square
                }
                const float d = depth[std::size_t(y) * kSize + std::size_t(x)];
                const double tangent = std::tan(camera.verticalFov / 2);
                const glm::dvec3 view(((x + 0.5) / kSize * 2 - 1) * tangent,
                                      (1 - (y + 0.5) / kSize * 2) * tangent, -1.0);
                const Geodetic g = Ellipsoid::toGeodetic(
                    camera.position + camera.axes * (view * (renderer_->near() / double(d))));
                const double east = (g.longitude / kDegree - kLongitude) * metresEast();
                const double north = (g.latitude / kDegree - kLatitude) * metresNorth();
                const double u = (20 - east) / 40 * 4, v = (north + 20) / 40 * 4;
                if (std::abs(u - std::round(u)) < 0.2 || std::abs(v - std::round(v)) < 0.2) {
                    continue;  // near a texel border: filtered between two colours
                }
                const int expected = quadTexel(int(u), int(v));
                const std::uint8_t* pixel =
                    lastImage_.pixels.data() + (std::size_t(y) * kSize + std::size_t(x)) * 4;
                int best = 0;
                double bestDistance = 1e9;
                const double sum = double(pixel[0]) + pixel[1] + pixel[2] + 1e-9;
                for (int c = 0; c < 4; ++c) {
                    const std::uint8_t* k = kQuadColors[c];
                    const double ksum = double(k[0]) + k[1] + k[2];
                    double distance = 0;
                    for (int i = 0; i < 3; ++i) {
                        distance += std::pow(pixel[i] / sum - k[i] / ksum, 2);
                    }
                    if (distance < bestDistance) {
                        bestDistance = distance;
                        best = c;
                    }
                }
                ++checked;
                ++seen[expected];
                wrong += best != expected;
            }
        }
        EXPECT_GT(checked, 2000);
        for (int c = 0; c < 4; ++c) {
            EXPECT_GT(seen[c], 100) << "colour " << c;
        }
        EXPECT_LE(wrong, checked / 200) << wrong << " of " << checked << " pixels";
    }
}

}  // namespace
}  // namespace sylva::render
