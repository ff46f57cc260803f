// MeshSimplifier on a finely tessellated unit sphere with split (per-face) vertices, as
// imported flat-shaded models have them: the levels weld the vertices, reduce to about a
// quarter of the triangles each, keep the surface within their recorded error (checked
// independently: every simplified vertex lies on the sphere, and the distance of the
// sphere's dense sample from the level stays within the error plus the sampling's own
// chord error), keep the colours, and have unit normals pointing outwards. A small part
// gets no levels.
#include "sylva/core/sources/objects/MeshSimplifier.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace sylva {
namespace {

// A UV sphere of radius 1 with every triangle's vertices its own (split), coloured by
// hemisphere; `textured`: texture coordinates (φ / 2π, θ / π), so the meridian φ = 0 is a
// seam (u = 0 on one side, 1 on the other) and the poles have one u per segment.
MeshGeometry splitSphere(int rings, int segments, bool textured = false) {
    MeshGeometry g;
    auto point = [&](int r, int s) {
        const double theta = std::numbers::pi * r / rings,
                     phi = 2 * std::numbers::pi * (s % segments) / segments;  // one seam position
        return glm::vec3(float(std::sin(theta) * std::cos(phi)),
                         float(std::sin(theta) * std::sin(phi)), float(std::cos(theta)));
    };
    auto uv = [&](int r, int s) {
        return textured ? glm::vec2(float(s) / float(segments), float(r) / float(rings))
                        : glm::vec2(0.0f);
    };
    auto add = [&](glm::ivec2 a, glm::ivec2 b, glm::ivec2 c) {
        const glm::vec3 pa = point(a.x, a.y), pb = point(b.x, b.y), pc = point(c.x, c.y);
        const glm::vec3 n = glm::normalize(glm::cross(pb - pa, pc - pa));
        for (const glm::ivec2& k : {a, b, c}) {
            const glm::vec3 p = point(k.x, k.y);
            g.indices.push_back(std::uint32_t(g.vertices.size()));
            g.vertices.push_back({p, n, p.z > 0 ? 0xff0000ffu : 0xffff0000u, uv(k.x, k.y)});
        }
    };
    for (int r = 0; r < rings; ++r)
        for (int s = 0; s < segments; ++s) {
            const glm::ivec2 a{r, s}, b{r + 1, s}, c{r + 1, s + 1}, d{r, s + 1};
            if (r > 0)
                add(a, b, d);
            if (r + 1 < rings)
                add(b, c, d);
        }
    return g;
}

TEST(MeshSimplifier, SphereLevelsShrinkAndStayWithinTheirError) {
    const MeshGeometry sphere = splitSphere(48, 96);  // 9,024 triangles
    const auto levels = simplifyLevels(sphere);
    ASSERT_GE(levels.size(), 3u);
    std::size_t previous = sphere.indices.size() / 3;
    double previousError = 0.0;
    for (const SimplifiedGeometry& level : levels) {
        const std::size_t triangles = level.geometry.indices.size() / 3;
        EXPECT_LE(triangles, previous * 3 / 10 + 4) << "about a quarter per level";
        EXPECT_GE(triangles, 32u);
        EXPECT_GE(level.errorMetres, previousError);
        EXPECT_GT(level.errorMetres, 0.0);
        EXPECT_LT(level.errorMetres, 0.5);
        for (const MeshVertex& v : level.geometry.vertices) {
            EXPECT_NEAR(glm::length(v.position), 1.0f, 1e-5f);  // collapses keep endpoints
            EXPECT_NEAR(glm::length(v.normal), 1.0f, 1e-4f);
            EXPECT_GT(glm::dot(v.normal, v.position), 0.3f) << "normals point outwards";
            EXPECT_EQ(v.color, v.position.z > 0 ? 0xff0000ffu : 0xffff0000u);
        }
        // Independent of the recorded error: the sphere's points near each face centre
        // lie within error + sagitta of the face (the face's centroid is at most that deep).
        for (std::size_t t = 0; t < level.geometry.indices.size(); t += 3) {
            const glm::vec3 centroid =
                (level.geometry.vertices[level.geometry.indices[t]].position +
                 level.geometry.vertices[level.geometry.indices[t + 1]].position +
                 level.geometry.vertices[level.geometry.indices[t + 2]].position) /
                3.0f;
            EXPECT_LE(1.0 - glm::length(centroid), level.errorMetres * 3.0 + 0.02);
        }
        previous = triangles;
        previousError = level.errorMetres;
    }
}

// Texture coordinates go through the levels as vertex properties: every simplified vertex
// keeps the (φ / 2π, θ / π) of its position, and the seam stays: each of the original seam
// vertices (φ = 0, between the poles) is in every level twice, with u = 0 and u = 1.
TEST(MeshSimplifier, TextureCoordinatesAndSeamsSurviveTheLevels) {
    const int rings = 48, segments = 96;
    const auto levels = simplifyLevels(splitSphere(rings, segments, true));
    ASSERT_GE(levels.size(), 2u);
    for (const SimplifiedGeometry& level : levels) {
        int seamLeft = 0, seamRight = 0;
        for (const MeshVertex& v : level.geometry.vertices) {
            const double theta = std::acos(std::clamp(double(v.position.z), -1.0, 1.0));
            EXPECT_NEAR(v.uv.y, theta / std::numbers::pi, 1e-4);
            const bool pole = std::abs(v.position.z) > 0.9999f;
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

TEST(MeshSimplifier, SmallPartsGetNoLevels) {
    const MeshGeometry small = splitSphere(8, 12);  // 168 triangles
    ASSERT_LT(small.indices.size() / 3, kSimplifyMinimumTriangles);
    EXPECT_TRUE(simplifyLevels(small).empty());
}

}  // namespace
}  // namespace sylva
