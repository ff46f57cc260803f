// DisplacedBillboardBuilder (DMBBC, seed 000 ch. 5): the thick-shell heights of a billboard
// quad span the analytic height of the geometry it simplifies over each texel.
#include <gtest/gtest.h>

#include <cmath>

#include "sylva/core/plantlod/DisplacedBillboardBuilder.h"

namespace sylva {
namespace {

// A 2 m × 2 m square tilted about x (y = 0.2 (z − 1.5)) and one billboard quad in the
// plane y = 0 facing −y that simplifies both its triangles; a 64² opaque atlas.
void tiltedSquare(PlantModel& model, BillboardLevel& level) {
    model.name = "tilted";
    PlantMesh mesh;
    mesh.part = PlantPart::Leaf;
    mesh.positions = {{-1, -0.2f, 0.5f}, {1, -0.2f, 0.5f}, {1, 0.2f, 2.5f}, {-1, 0.2f, 2.5f}};
    mesh.indices = {0, 1, 2, 0, 2, 3};
    model.meshes.push_back(mesh);
    BillboardQuad quad;
    quad.corners[0] = {-1, 0, 0.5f};
    quad.corners[1] = {1, 0, 0.5f};
    quad.corners[2] = {1, 0, 2.5f};
    quad.corners[3] = {-1, 0, 2.5f};
    quad.atlasUvs[0] = {0, 1};
    quad.atlasUvs[1] = {1, 1};
    quad.atlasUvs[2] = {1, 0};
    quad.atlasUvs[3] = {0, 0};
    quad.normal = {0, -1, 0};
    level.epsilon = 0.25f;
    level.quads = {quad};
    level.trianglePlane = {0, 0};
    level.atlas.width = level.atlas.height = 64;
    level.atlas.rgba.assign(64 * 64 * 4, 255);
}

TEST(DisplacedBillboardBuilder, ShellHeightsAreTheGeometrysHeightAboveThePlane) {
    PlantModel model;
    BillboardLevel level;
    tiltedSquare(model, level);
    Result<DisplacementAtlas> atlas = DisplacedBillboardBuilder::build(model, level);
    ASSERT_TRUE(atlas) << atlas.error().message;
    ASSERT_EQ(atlas->width, 64);
    ASSERT_EQ(atlas->heights.size(), 64u * 64u);
    for (int y = 0; y < 64; ++y) {
        // Row y (from the top) is at z = 2.5 − 2 (y + 0.5) / 64; height along −y = −0.2 (z − 1.5).
        const float z = 2.5f - 2.0f * (float(y) + 0.5f) / 64.0f;
        const float expected = -0.2f * (z - 1.5f);
        for (int x = 0; x < 64; ++x) {
            const glm::vec2 shell = atlas->heights[std::size_t(y) * 64 + x];
            // The texel's interval spans the surface over the texel: half a row's height
            // step (0.4 m / 64 rows) either way, except outward at the first and last row.
            constexpr float kHalfStep = 0.2f * 2.0f / 64.0f / 2.0f;
            const float below = y == 0 ? 0.0f : kHalfStep, above = y == 63 ? 0.0f : kHalfStep;
            ASSERT_NEAR(shell.x, expected - below, 1e-4f) << x << "," << y;
            ASSERT_NEAR(shell.y, expected + above, 1e-4f) << x << "," << y;
        }
    }
    ASSERT_EQ(atlas->halfThickness.size(), 1u);
    EXPECT_NEAR(atlas->halfThickness[0], 0.2f * (1.0f - 1.0f / 64.0f), 1e-4f);
}

TEST(DisplacedBillboardBuilder, LevelOfAnotherModelFailsNamingIt) {
    PlantModel model;
    BillboardLevel level;
    tiltedSquare(model, level);
    level.trianglePlane.push_back(0);  // three triangles assigned, the model has two
    Result<DisplacementAtlas> atlas = DisplacedBillboardBuilder::build(model, level);
    ASSERT_FALSE(atlas);
    EXPECT_NE(atlas.error().message.find("'tilted'"), std::string::npos);
}

}  // namespace
}  // namespace sylva
