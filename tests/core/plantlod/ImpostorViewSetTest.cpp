// ImpostorViewSet (issue 21, seed 004 §3.2, §3.4): every direction of the upper
// hemisphere is within the stated gap of its nearest view (sampled densely, against the
// brute-force nearest), each view is its own nearest, and the resolution is the smallest
// of 64/128/256 that covers the plant's pixels.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "sylva/core/plantlod/ImpostorViewSet.h"

namespace sylva {
namespace {

TEST(ImpostorViewSetTest, EveryUpperDirectionIsNearAView) {
    const ImpostorViewSet set = ImpostorViewSet::upperHemisphere();
    ASSERT_EQ(set.size(), 17u);
    double largest = 0.0;
    for (int e = 0; e <= 90; ++e) {
        for (int a = 0; a < 360; ++a) {
            const double elevation = e * std::numbers::pi / 180,
                         azimuth = a * std::numbers::pi / 180;
            const glm::dvec3 d(std::cos(elevation) * std::cos(azimuth),
                               std::cos(elevation) * std::sin(azimuth), std::sin(elevation));
            double bestAngle = 1e9;
            for (const glm::vec3& v : set.directions()) {
                bestAngle = std::min(bestAngle,
                                     std::acos(std::clamp(glm::dot(d, glm::dvec3(v)), -1.0, 1.0)));
            }
            const glm::dvec3 chosen(set.directions()[std::size_t(set.nearest(glm::vec3(d)))]);
            EXPECT_NEAR(std::acos(std::clamp(glm::dot(d, chosen), -1.0, 1.0)), bestAngle, 1e-5);
            largest = std::max(largest, bestAngle * 180 / std::numbers::pi);
        }
    }
    EXPECT_LE(largest, ImpostorViewSet::kLargestViewGap);
    EXPECT_GT(largest, ImpostorViewSet::kLargestViewGap - 5.0);  // the bound is not loose
    for (std::size_t i = 0; i < set.size(); ++i) {
        EXPECT_EQ(set.nearest(set.directions()[i]), int(i));
    }
}

TEST(ImpostorViewSetTest, ResolutionCoversThePixels) {
    EXPECT_EQ(ImpostorViewSet::resolutionLevel(3.0), 0);
    EXPECT_EQ(ImpostorViewSet::resolutionLevel(64.0), 0);
    EXPECT_EQ(ImpostorViewSet::resolutionLevel(64.5), 1);
    EXPECT_EQ(ImpostorViewSet::resolutionLevel(200.0), 2);
    EXPECT_EQ(ImpostorViewSet::resolutionLevel(5000.0), 2);
}

}  // namespace
}  // namespace sylva
