// MeshSimplifier with texture coordinates: a textured unit sphere (a seam along one
// meridian) simplified; every level's vertices keep the texture coordinates of their
// positions (OpenMesh vertex properties) and the seam vertices stay, on both sides.
#include "sylva/core/sources/objects/MeshSimplifier.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace sylva {
namespace {

// The same sphere shared (not split) and textured with (φ / 2π, θ / π): the meridian φ = 0
// is a seam (one position, u = 0 on one side and u = 1 on the other); the poles are single
// vertices (u = 0.5).
MeshGeometry texturedSphere(int rings, int segments) {
    MeshGeometry g;
    const auto corner = [&](int r, int s) {
        const double theta = std::numbers::pi * r / rings,
                     phi = 2 * std::numbers::pi * (s % segments) / segments;
        MeshVertex v;
        v.position = glm::vec3(float(std::sin(theta) * std::cos(phi)),
                               float(std::sin(theta) * std::sin(phi)), float(std::cos(theta)));
        v.normal = v.position;
        const bool pole = r == 0 || r == rings;
        v.uv = glm::vec2(pole ? 0.5f : float(s) / float(segments), float(r) / float(rings));
        g.vertices.push_back(v);
        return std::uint32_t(g.vertices.size() - 1);
    };
    std::vector<std::uint32_t> index((rings + 1) * (segments + 1));
    for (int r = 0; r <= rings; ++r)
        for (int s = 0; s <= segments; ++s)
            index[std::size_t(r * (segments + 1) + s)] =
                (r == 0 || r == rings) && s > 0 ? index[std::size_t(r * (segments + 1))]
                                                : corner(r, s);
    const auto at = [&](int r, int s) { return index[std::size_t(r * (segments + 1) + s)]; };
    for (int r = 0; r < rings; ++r)
        for (int s = 0; s < segments; ++s) {
            if (r > 0)
                g.indices.insert(g.indices.end(), {at(r, s), at(r + 1, s), at(r, s + 1)});
            if (r + 1 < rings)
                g.indices.insert(g.indices.end(), {at(r + 1, s), at(r + 1, s + 1), at(r, s + 1)});
        }
    return g;
}

// Texture coordinates go through the levels as vertex properties: every simplified vertex
// keeps the (φ / 2π, θ / π) of its position, and the seam stays: each of the original seam
// vertices (φ = 0, between the poles) is in every level twice, with u = 0 and u = 1.
TEST(MeshSimplifier, TextureCoordinatesAndSeamsSurviveTheLevels) {
    const int rings = 48, segments = 96;
    const auto levels = simplifyLevels(texturedSphere(rings, segments));
    ASSERT_GE(levels.size(), 1u);
    for (const SimplifiedGeometry& level : levels) {
        int seamLeft = 0, seamRight = 0;
        for (const MeshVertex& v : level.geometry.vertices) {
            const double theta = std::acos(std::clamp(double(v.position.z), -1.0, 1.0));
            EXPECT_NEAR(v.uv.y, theta / std::numbers::pi, 1e-4);
            const bool pole = std::abs(v.position.z) > 0.99999f;
            if (pole) {
                continue;  // φ is undefined at the poles
            }
            double phi = std::atan2(double(v.position.y), double(v.position.x));
            phi = phi < -1e-6 ? phi + 2 * std::numbers::pi : std::max(phi, 0.0);
            const bool onSeam = std::abs(v.position.y) < 1e-6f && v.position.x > 0;
            if (onSeam) {
                seamLeft += v.uv.x == 0.0f;
                seamRight += v.uv.x == 1.0f;
            } else {
                EXPECT_NEAR(v.uv.x, phi / (2 * std::numbers::pi), 1e-4);
            }
        }
        EXPECT_EQ(seamLeft, rings - 1);
        EXPECT_EQ(seamRight, rings - 1);
    }
}

}  // namespace
}  // namespace sylva
