#include "sylva/core/terrain/TerrainRings.h"

#include <gtest/gtest.h>

#include <cstring>
#include <numbers>

namespace sylva {
namespace {

bool bitEqual(float a, float b) {
    return std::memcmp(&a, &b, sizeof a) == 0;
}

TEST(TerrainRings, LevelBordersAreBitIdentical) {
    for (auto [columns, rings] : {std::pair{64, 16}, std::pair{48, 12}, std::pair{8, 3}}) {
        const TerrainRings mesh(columns, rings);
        const auto& ring = mesh.ringMesh().vertices;
        const auto& fill = mesh.fillMesh().vertices;
        const int stride = columns + 1;
        ASSERT_EQ(ring.size(), std::size_t(stride) * (rings + 1));
        ASSERT_EQ(fill.size(), std::size_t(stride) * (2 * rings + 1) + 1);
        for (int c = 0; c < stride; ++c) {
            const TerrainVertex& outer = ring[c];
            const TerrainVertex& inner = ring[std::size_t(rings) * stride + c];
            const TerrainVertex& fillOuter = fill[c];
            EXPECT_TRUE(bitEqual(outer.viewAngle, static_cast<float>(std::numbers::pi)));
            EXPECT_TRUE(bitEqual(inner.viewAngle, fillOuter.viewAngle))
                << columns << "/" << rings << " c " << c;
            EXPECT_TRUE(bitEqual(inner.viewAngle, outer.viewAngle * 0.5f));
            EXPECT_TRUE(bitEqual(inner.sinBearing, fillOuter.sinBearing));
            EXPECT_TRUE(bitEqual(inner.cosBearing, fillOuter.cosBearing));
            // Fill border rings at each further level are exact halvings too.
            EXPECT_TRUE(
                bitEqual(fill[std::size_t(rings) * stride + c].viewAngle, outer.viewAngle * 0.25f));
        }
        // View angles decrease monotonically inwards.
        for (int row = 1; row <= rings; ++row) {
            EXPECT_LT(ring[std::size_t(row) * stride].viewAngle,
                      ring[std::size_t(row - 1) * stride].viewAngle);
        }
        EXPECT_EQ(fill.back().viewAngle, 0.0f);
    }
}

TEST(TerrainRings, BlendWeightIsOneOutsideAndZeroInside) {
    const int columns = 32, rings = 10;
    const TerrainRings mesh(columns, rings);
    const auto& ring = mesh.ringMesh().vertices;
    const int stride = columns + 1;
    for (int c = 0; c < stride; ++c) {
        EXPECT_EQ(ring[c].blend, 1.0f);
        EXPECT_EQ(ring[std::size_t(rings) * stride + c].blend, 0.0f);
    }
    for (int row = 1; row <= rings; ++row) {
        EXPECT_LE(ring[std::size_t(row) * stride].blend, ring[std::size_t(row - 1) * stride].blend);
    }
    for (const TerrainVertex& v : mesh.fillMesh().vertices) {
        EXPECT_EQ(v.blend, 0.0f);
    }
}

TEST(TerrainRings, SeamFlagsOnlyOnFirstAndLastColumn) {
    const int columns = 16, rings = 4;
    const TerrainRings mesh(columns, rings);
    const int stride = columns + 1;
    for (const TerrainMesh* m : {&mesh.ringMesh(), &mesh.fillMesh()}) {
        const std::size_t gridVertices = m->vertices.size() - (m == &mesh.fillMesh() ? 1 : 0);
        for (std::size_t i = 0; i < gridVertices; ++i) {
            const int column = int(i % stride);
            const float expected = column == 0 ? 1.0f : (column == columns ? -1.0f : 0.0f);
            EXPECT_EQ(m->vertices[i].seam, expected) << i;
        }
        for (std::uint32_t index : m->indices) {
            EXPECT_LT(index, m->vertices.size());
        }
        EXPECT_EQ(m->indices.size() % 3, 0u);
    }
    // The duplicated last column has the same bearing as the first.
    const auto& ring = mesh.ringMesh().vertices;
    EXPECT_EQ(ring[0].sinBearing, ring[columns].sinBearing);
    EXPECT_EQ(ring[0].cosBearing, ring[columns].cosBearing);
}

}  // namespace
}  // namespace sylva
