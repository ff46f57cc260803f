// DepthPyramid (issue 21, occlusion culling): a sphere reported hidden has no pixel where
// a ray through the pixel centre meets it in front of the stored depth (a brute-force
// ray cast per pixel is the oracle, on random spheres over a ridge-and-blocks depth
// image with a lens-shifted projection); a sphere just visible over a ridge is never
// hidden, one below it is; the coarse levels keep the farthest depth of their pixels.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "sylva/core/vegetation/DepthPyramid.h"

namespace sylva {
namespace {

constexpr int kWidth = 160, kHeight = 90;
constexpr double kNear = 0.5;

// SceneRenderer::projection's layout: p00, p11 the focal scales, p20, p21 the lens shift.
glm::dmat4 projection(double verticalFov, double aspect, glm::dvec2 shift = glm::dvec2(0.0)) {
    const double f = 1.0 / std::tan(verticalFov / 2);
    glm::dmat4 p(0.0);
    p[0][0] = f / aspect;
    p[1][1] = f;
    p[2][0] = 2.0 * shift.x;
    p[2][1] = 2.0 * shift.y;
    p[2][3] = -1.0;
    p[3][2] = kNear;
    return p;
}

// The view-space direction (z = -1) through the centre of pixel (x, y), y from the bottom.
glm::dvec3 pixelRay(const glm::dmat4& p, int x, int y) {
    const double ndcX = (x + 0.5) / kWidth * 2 - 1, ndcY = (y + 0.5) / kHeight * 2 - 1;
    return glm::dvec3((ndcX + p[2][0]) / p[0][0], (ndcY + p[2][1]) / p[1][1], -1.0);
}

// Oracle: whether any pixel's ray meets the sphere at a depth passing GREATER against the
// stored depth (depth = near / axial distance of the nearest hit).
bool visibleByRayCast(const std::vector<float>& depth, const glm::dmat4& p, glm::dvec3 center,
                      double radius) {
    for (int y = 0; y < kHeight; ++y) {
        for (int x = 0; x < kWidth; ++x) {
            const glm::dvec3 d = pixelRay(p, x, y);
            // |t d - c|² = r²: the nearest t (axial distance, since d.z = -1).
            const double a = glm::dot(d, d), b = glm::dot(d, center);
            const double disc = b * b - a * (glm::dot(center, center) - radius * radius);
            if (disc < 0) {
                continue;
            }
            const double t = (b - std::sqrt(disc)) / a;
            if (t > kNear && kNear / t > depth[std::size_t(y) * kWidth + x]) {
                return true;
            }
        }
    }
    return false;
}

// Terrain: a ridge 40 m ahead up to row 45 (from the bottom), sky above; two blocks of
// nearer canopy and a hole through the ridge showing far terrain.
std::vector<float> ridgeDepth() {
    std::vector<float> depth(std::size_t(kWidth) * kHeight, 0.0f);
    for (int y = 0; y < kHeight; ++y) {
        for (int x = 0; x < kWidth; ++x) {
            float& d = depth[std::size_t(y) * kWidth + x];
            if (y < 45) {
                d = float(kNear / 40.0);
            }
            if (x >= 20 && x < 50 && y >= 30 && y < 70) {
                d = float(kNear / 15.0);
            }
            if (x >= 100 && x < 104 && y < 45) {
                d = float(kNear / 400.0);  // a notch in the ridge
            }
        }
    }
    return depth;
}

TEST(DepthPyramid, HiddenSpheresAreNeverSeenByAnyPixelRay) {
    const std::vector<float> depth = ridgeDepth();
    const glm::dmat4 p = projection(0.8, double(kWidth) / kHeight, {0.07, -0.04});
    DepthPyramid pyramid;
    pyramid.build(depth, kWidth, kHeight, p, kNear);
    ASSERT_FALSE(pyramid.empty());
    std::mt19937 random(5);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    int hidden = 0, visible = 0;
    for (int i = 0; i < 1500; ++i) {
        const double distance = 5.0 + 200.0 * unit(random);
        const glm::dvec3 center((unit(random) - 0.5) * distance, (unit(random) - 0.7) * distance,
                                -distance);
        const double radius = 0.2 + 8.0 * unit(random) * unit(random);
        const bool seen = visibleByRayCast(depth, p, center, radius);
        const bool culled = pyramid.hidden(glm::vec3(center), float(radius));
        ASSERT_FALSE(culled && seen)
            << "sphere at " << center.x << ", " << center.y << ", " << center.z << " r " << radius;
        hidden += culled ? 1 : 0;
        visible += seen ? 1 : 0;
    }
    // The test is useful, not only safe: most spheres behind the ridge are culled.
    EXPECT_GT(hidden, 300);
    EXPECT_GT(visible, 300);
}

// A tree 100 m ahead whose top reaches just over the ridge (its top tangent 0.3 px above
// the centre of the ridge's first sky row) is visible by one row of pixels and must not be
// culled; lowered by four pixels it is wholly behind the ridge and is culled.
TEST(DepthPyramid, AnInstanceJustVisibleOverARidgeIsNeverCulled) {
    const std::vector<float> depth = ridgeDepth();
    const glm::dmat4 p = projection(0.8, double(kWidth) / kHeight);
    DepthPyramid pyramid;
    pyramid.build(depth, kWidth, kHeight, p, kNear);
    const double radius = 3.0, axial = 100.0;
    // Pixel row y (from the bottom) of tangent ty: (ty p11 + 1) / 2 · height.
    const auto tangentOfRow = [&](double row) { return (row / kHeight * 2 - 1) / p[1][1]; };
    for (const double topRow : {45.5 + 0.3, 45.5 - 4.0}) {
        // The top tangent of a sphere at (0, cy, -axial): ty = (cy a + r sqrt(cy² + a² - r²))
        // / (a² - r²); solve for cy numerically (monotone in cy).
        const double target = tangentOfRow(topRow);
        double low = -axial, high = axial;
        for (int it = 0; it < 100; ++it) {
            const double cy = 0.5 * (low + high);
            const double ty =
                (cy * axial + radius * std::sqrt(cy * cy + axial * axial - radius * radius)) /
                (axial * axial - radius * radius);
            (ty < target ? low : high) = cy;
        }
        const glm::dvec3 center(10.0, 0.5 * (low + high), -axial);  // clear of block and notch
        const bool seen = visibleByRayCast(depth, p, center, radius);
        EXPECT_EQ(seen, topRow > 45.5) << "fixture: top row " << topRow;
        EXPECT_EQ(pyramid.hidden(glm::vec3(center), float(radius)), !seen) << topRow;
    }
    // The same sphere in front of the ridge, or reaching the near plane, is never hidden.
    EXPECT_FALSE(pyramid.hidden(glm::vec3(0.0f, -10.0f, -30.0f), 3.0f));
    EXPECT_FALSE(pyramid.hidden(glm::vec3(0.0f, -1.0f, -0.6f), 0.2f));
}

TEST(DepthPyramid, CoarseLevelsKeepTheFarthestDepthAndEmptyHidesNothing) {
    std::vector<float> depth(std::size_t(kWidth) * kHeight, 0.5f);
    depth[std::size_t(77) * kWidth + 133] = 0.01f;  // one far pixel
    DepthPyramid pyramid;
    pyramid.build(depth, kWidth, kHeight, projection(0.8, 1.6), kNear);
    EXPECT_EQ(pyramid.farthestDepth(0, 0, kWidth - 1, kHeight - 1), 0.01f);
    EXPECT_EQ(pyramid.farthestDepth(130, 70, 140, 80), 0.01f);
    EXPECT_EQ(pyramid.farthestDepth(0, 0, 60, 40), 0.5f);
    EXPECT_EQ(pyramid.farthestDepth(-50, -50, -1, -1), std::numeric_limits<float>::infinity());
    DepthPyramid none;
    EXPECT_FALSE(none.hidden(glm::vec3(0.0f, 0.0f, -1000.0f), 1.0f));
    // A wrong depth count leaves the pyramid empty rather than reading out of bounds.
    none.build(std::vector<float>(10, 1.0f), kWidth, kHeight, projection(0.8, 1.6), kNear);
    EXPECT_TRUE(none.empty());
}

}  // namespace
}  // namespace sylva
