// HipRoof (the straight skeleton's roof of a convex footprint) against analytic roofs: a
// rectangle L × W at pitch θ has a ridge of length L − W at height W/2 · tan θ and a roof
// area of L · W / cos θ (every face slopes at θ, so its area is its plan area / cos θ);
// a regular hexagon's roof is a pyramid with its apex at the inradius · tan θ; every
// corner's height is the lower envelope eaves + tan θ · (distance to the nearest side);
// the faces tile the footprint.
#include "sylva/core/sources/objects/HipRoof.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace sylva {
namespace {

constexpr double kPitch = 35.0 * std::numbers::pi / 180.0;
constexpr double kEaves = 6.0;

double planArea(const std::vector<glm::dvec3>& face) {
    double area = 0.0;
    for (std::size_t i = 0; i < face.size(); ++i) {
        const glm::dvec3 a = face[i], b = face[(i + 1) % face.size()];
        area += a.x * b.y - b.x * a.y;
    }
    return 0.5 * area;
}

double surfaceArea(const std::vector<glm::dvec3>& face) {
    glm::dvec3 sum(0.0);
    for (std::size_t i = 1; i + 1 < face.size(); ++i) {
        sum += glm::cross(face[i] - face[0], face[i + 1] - face[0]);
    }
    return 0.5 * glm::length(sum);
}

// The analytic lower envelope over a convex CCW ring.
double envelope(const std::vector<glm::dvec2>& ring, const glm::dvec2& p) {
    double nearest = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < ring.size(); ++i) {
        const glm::dvec2 a = ring[i], d = ring[(i + 1) % ring.size()] - a;
        nearest = std::min(nearest, (d.x * (p.y - a.y) - d.y * (p.x - a.x)) / glm::length(d));
    }
    return kEaves + std::tan(kPitch) * nearest;
}

void expectOnEnvelopeAndTiling(const std::vector<glm::dvec2>& ring,
                               const std::vector<HipRoofFace>& faces) {
    double plan = 0.0, footprint = 0.0;
    for (const HipRoofFace& face : faces) {
        EXPECT_GT(planArea(face.corners), 0.0) << "counter-clockwise from above";
        plan += planArea(face.corners);
        for (const glm::dvec3& c : face.corners) {
            EXPECT_NEAR(c.z, envelope(ring, {c.x, c.y}), 1e-9);
        }
    }
    for (std::size_t i = 0; i < ring.size(); ++i) {
        const glm::dvec2 a = ring[i], b = ring[(i + 1) % ring.size()];
        footprint += 0.5 * (a.x * b.y - b.x * a.y);
    }
    EXPECT_NEAR(plan, footprint, 1e-9 * footprint);
}

TEST(HipRoof, RectangleHasTheAnalyticRidgeAndArea) {
    const double length = 24.0, width = 10.0;
    // Rotated by 30° and shifted: the result must not depend on the axes.
    const double a = 30.0 * std::numbers::pi / 180.0;
    const glm::dvec2 u(std::cos(a), std::sin(a)), v(-std::sin(a), std::cos(a)), o(5.0, -3.0);
    const std::vector<glm::dvec2> ring = {o, o + length * u, o + length * u + width * v,
                                          o + width * v};
    const std::vector<HipRoofFace> faces = hipRoof(ring, kEaves, kPitch);
    ASSERT_EQ(faces.size(), 4u);
    double area = 0.0;
    std::vector<glm::dvec3> ridge;
    const double top = kEaves + 0.5 * width * std::tan(kPitch);
    for (const HipRoofFace& face : faces) {
        area += surfaceArea(face.corners);
        for (const glm::dvec3& c : face.corners) {
            EXPECT_LE(c.z, top + 1e-9);
            if (std::abs(c.z - top) < 1e-9 &&
                std::none_of(ridge.begin(), ridge.end(),
                             [&](const glm::dvec3& r) { return glm::length(r - c) < 1e-6; })) {
                ridge.push_back(c);
            }
        }
    }
    ASSERT_EQ(ridge.size(), 2u);
    EXPECT_NEAR(glm::length(ridge[0] - ridge[1]), length - width, 1e-9);
    EXPECT_NEAR(area, length * width / std::cos(kPitch), 1e-9 * area);
    expectOnEnvelopeAndTiling(ring, faces);
}

TEST(HipRoof, RegularHexagonIsAPyramidAndAPentagonTilesItsFootprint) {
    std::vector<glm::dvec2> hexagon;
    const double radius = 8.0;
    for (int i = 0; i < 6; ++i) {
        const double t = i * std::numbers::pi / 3.0;
        hexagon.emplace_back(radius * std::cos(t), radius * std::sin(t));
    }
    const std::vector<HipRoofFace> faces = hipRoof(hexagon, kEaves, kPitch);
    ASSERT_EQ(faces.size(), 6u);
    const double apex = kEaves + radius * std::cos(std::numbers::pi / 6.0) * std::tan(kPitch);
    for (const HipRoofFace& face : faces) {
        const double highest =
            std::max_element(face.corners.begin(), face.corners.end(),
                             [](const glm::dvec3& p, const glm::dvec3& q) { return p.z < q.z; })
                ->z;
        EXPECT_NEAR(highest, apex, 1e-9);
        EXPECT_EQ(face.corners.size(), 3u);
    }
    expectOnEnvelopeAndTiling(hexagon, faces);
    // An irregular convex pentagon (a house with a bay), with a collinear extra corner.
    const std::vector<glm::dvec2> pentagon = {{0, 0}, {10, 0}, {20, 0}, {22, 8}, {12, 14}, {-1, 9}};
    const std::vector<HipRoofFace> roof = hipRoof(pentagon, kEaves, kPitch);
    EXPECT_GE(roof.size(), 5u);
    expectOnEnvelopeAndTiling(pentagon, roof);
}

}  // namespace
}  // namespace sylva
