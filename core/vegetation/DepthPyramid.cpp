#include "sylva/core/vegetation/DepthPyramid.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sylva {

namespace {

// The tangent range (x / -z) of a circle of radius r centred at (u, v), v = axial
// distance > r: the two lines through the origin tangent to it (exact, so the extent of
// the sphere's perspective image along one axis; Mara & McGuire 2013, eq. 3).
void tangentRange(double u, double v, double r, double& low, double& high) {
    const double denominator = v * v - r * r;
    const double root = r * std::sqrt(std::max(u * u + denominator, 0.0));
    low = (u * v - root) / denominator;
    high = (u * v + root) / denominator;
}

}  // namespace

void DepthPyramid::clear() {
    levels_.clear();
}

void DepthPyramid::build(std::span<const float> depth, int width, int height,
                         const glm::dmat4& projection, double near) {
    if (width < 1 || height < 1 || depth.size() != std::size_t(width) * std::size_t(height)) {
        levels_.clear();
        return;
    }
    near_ = near;
    scale_ = glm::dvec2(0.5 * width * projection[0][0], 0.5 * height * projection[1][1]);
    offset_ =
        glm::dvec2(0.5 * width * (1.0 - projection[2][0]), 0.5 * height * (1.0 - projection[2][1]));
    // Keep the levels' storage from frame to frame: resize, then overwrite.
    int levelCount = 1;
    for (int w = width, h = height; w > 1 || h > 1; w = (w + 1) / 2, h = (h + 1) / 2) {
        ++levelCount;
    }
    levels_.resize(std::size_t(levelCount));
    levels_[0].width = width;
    levels_[0].height = height;
    levels_[0].depth.assign(depth.begin(), depth.end());
    for (std::size_t l = 1; l < levels_.size(); ++l) {
        const Level& fine = levels_[l - 1];
        Level& coarse = levels_[l];
        coarse.width = (fine.width + 1) / 2;
        coarse.height = (fine.height + 1) / 2;
        coarse.depth.resize(std::size_t(coarse.width) * std::size_t(coarse.height));
        for (int y = 0; y < coarse.height; ++y) {
            const int y0 = 2 * y, y1 = std::min(2 * y + 1, fine.height - 1);
            const float* row0 = fine.depth.data() + std::size_t(y0) * std::size_t(fine.width);
            const float* row1 = fine.depth.data() + std::size_t(y1) * std::size_t(fine.width);
            float* out = coarse.depth.data() + std::size_t(y) * std::size_t(coarse.width);
            for (int x = 0; x < coarse.width; ++x) {
                const int x0 = 2 * x, x1 = std::min(2 * x + 1, fine.width - 1);
                out[x] = std::min(std::min(row0[x0], row0[x1]), std::min(row1[x0], row1[x1]));
            }
        }
    }
}

float DepthPyramid::farthestDepth(int x0, int y0, int x1, int y1) const {
    if (empty()) {
        return 0.0f;
    }
    x0 = std::max(x0, 0);
    y0 = std::max(y0, 0);
    x1 = std::min(x1, levels_[0].width - 1);
    y1 = std::min(y1, levels_[0].height - 1);
    if (x0 > x1 || y0 > y1) {
        return std::numeric_limits<float>::infinity();  // nothing of the image
    }
    std::size_t l = 0;
    while (l + 1 < levels_.size() && ((x1 >> l) - (x0 >> l) > 3 || (y1 >> l) - (y0 >> l) > 3)) {
        ++l;
    }
    const Level& level = levels_[l];
    float farthest = std::numeric_limits<float>::infinity();
    for (int y = y0 >> l; y <= (y1 >> l); ++y) {
        const float* row = level.depth.data() + std::size_t(y) * std::size_t(level.width);
        for (int x = x0 >> l; x <= (x1 >> l); ++x) {
            farthest = std::min(farthest, row[x]);
        }
    }
    return farthest;
}

bool DepthPyramid::hidden(const glm::vec3& center, float radius) const {
    if (empty()) {
        return false;
    }
    const double r = radius;
    const double axial = -double(center.z);
    if (axial - r <= near_ * (1.0 + 1e-6)) {
        return false;  // reaches the near plane (or behind the eye): never hidden
    }
    // Depth of the sphere's nearest point along the axis: the largest depth any fragment
    // of its contents can have.
    const double nearestDepth = near_ / (axial - r);
    double lowX = 0.0, highX = 0.0, lowY = 0.0, highY = 0.0;
    tangentRange(double(center.x), axial, r, lowX, highX);
    tangentRange(double(center.y), axial, r, lowY, highY);
    // Fragments are sampled at pixel centres inside the image of the sphere: pixels whose
    // centre lies in [low, high], widened by a pixel for rounding.
    const double left = scale_.x * lowX + offset_.x, right = scale_.x * highX + offset_.x;
    const double bottom = scale_.y * lowY + offset_.y, top = scale_.y * highY + offset_.y;
    constexpr double kLimit = 1e9;  // keeps the int conversion defined
    const int x0 = int(std::floor(std::clamp(left - 0.5, -kLimit, kLimit))) - 1;
    const int x1 = int(std::ceil(std::clamp(right - 0.5, -kLimit, kLimit))) + 1;
    const int y0 = int(std::floor(std::clamp(bottom - 0.5, -kLimit, kLimit))) - 1;
    const int y1 = int(std::ceil(std::clamp(top - 0.5, -kLimit, kLimit))) + 1;
    const float farthest = farthestDepth(x0, y0, x1, y1);
    return float(nearestDepth) * (1.0f + kDepthMargin) < farthest;
}

}  // namespace sylva
