// PointCloudBuilder (seed 000 ch. 3): samples lie on the mesh with its normal, carry the
// texture's colour at their position, leave the alpha-tested holes empty, and their count
// and radius follow the area — all checked against the analytic square below.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "sylva/core/plantlod/PointCloudBuilder.h"

namespace sylva {
namespace {

// A 2 m × 2 m square at z = 0.5 (normal +Z), textured 2 × 2: red left, green right,
// the top-right texel transparent (alpha-masked material).
PlantModel texturedSquare() {
    PlantModel model;
    model.name = "square";
    PlantMaterial material;
    material.alphaMasked = true;
    material.alphaCutoff = 0.5f;
    material.baseColorTexture.width = 2;
    material.baseColorTexture.height = 2;
    // Rows from the top: (0,0) red, (1,0) transparent green, (0,1) red, (1,1) green.
    material.baseColorTexture.rgba = {255, 0, 0, 255, 0, 255, 0, 0, 255, 0, 0, 255, 0, 255, 0, 255};
    model.materials.push_back(material);
    PlantMesh mesh;
    mesh.part = PlantPart::Leaf;
    mesh.material = 0;
    mesh.positions = {{-1, -1, 0.5f}, {1, -1, 0.5f}, {1, 1, 0.5f}, {-1, 1, 0.5f}};
    mesh.normals.assign(4, glm::vec3(0, 0, 1));
    // uv v runs down the texture rows: y = +1 is the top row.
    mesh.uvs = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
    mesh.indices = {0, 1, 2, 0, 2, 3};
    model.meshes.push_back(mesh);
    return model;
}

TEST(PointCloudBuilder, SamplesLieOnTheSurfaceWithTheTexturesColourAndHoles) {
    PointCloudOptions options;
    options.samples = 20000;
    Result<PointCloud> cloud = PointCloudBuilder::build(texturedSquare(), options);
    ASSERT_TRUE(cloud) << cloud.error().message;
    // A quarter of the square is transparent: 15,000 expected, binomial noise ~1 %.
    EXPECT_NEAR(double(cloud->points.size()), 15000.0, 300.0);
    const float radius =
        float(std::sqrt(options.coverage * 4.0 / options.samples / std::numbers::pi));
    for (const PlantPoint& p : cloud->points) {
        EXPECT_FLOAT_EQ(p.position.z, 0.5f);
        ASSERT_LE(std::abs(p.position.x), 1.0f);
        ASSERT_LE(std::abs(p.position.y), 1.0f);
        EXPECT_FLOAT_EQ(p.normal.z, 1.0f);
        EXPECT_FLOAT_EQ(p.radius, radius);
        // The transparent texel is the top-right quadrant.
        ASSERT_FALSE(p.position.x > 0.001f && p.position.y > 0.001f)
            << p.position.x << " " << p.position.y;
        const glm::vec3 color = PointCloudBuilder::unpackColor(p.color);
        if (p.position.x < -0.001f) {
            ASSERT_EQ(color, glm::vec3(1, 0, 0));
        } else if (p.position.x > 0.001f) {
            ASSERT_EQ(color, glm::vec3(0, 1, 0));
        }
    }
}

TEST(PointCloudBuilder, ColourPackingRoundTripsWithinOneCode) {
    for (float c : {0.0f, 0.002f, 0.05f, 0.2f, 0.7f, 1.0f}) {
        const glm::vec3 back =
            PointCloudBuilder::unpackColor(PointCloudBuilder::packColor(glm::vec3(c)));
        EXPECT_NEAR(back.r, c, std::max(0.0015f, 0.02f * c)) << c;
    }
}

TEST(PointCloudBuilder, ModelWithoutTrianglesFailsNamingIt) {
    PlantModel model;
    model.name = "bare";
    Result<PointCloud> cloud = PointCloudBuilder::build(model);
    ASSERT_FALSE(cloud);
    EXPECT_NE(cloud.error().message.find("'bare'"), std::string::npos);
    PointCloudOptions bad;
    bad.samples = 0;
    EXPECT_FALSE(PointCloudBuilder::build(texturedSquare(), bad));
}

}  // namespace
}  // namespace sylva
