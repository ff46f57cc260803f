#include "sylva/core/plantlod/ImageErrorMetric.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace sylva {
namespace {

TEST(ImageErrorMetric, SinglePassEqualsDirectPerLevelComputation) {
    for (int size : {1, 2, 8, 64, 256}) {
        std::mt19937 random(size);
        std::uniform_real_distribution<float> unit(0.0f, 1.0f);
        std::vector<float> a(size * size), b(size * size);
        for (int i = 0; i < size * size; ++i) {
            a[i] = unit(random);
            b[i] = unit(random) * 0.5f;
        }
        const auto single = multiScaleSquaredErrors(a, b, size);
        const auto direct = multiScaleSquaredErrorsDirect(a, b, size);
        ASSERT_EQ(single.size(), direct.size());
        ASSERT_EQ(single.size(), static_cast<std::size_t>(std::log2(size)) + 1);
        for (std::size_t k = 0; k < single.size(); ++k) {
            EXPECT_NEAR(single[k], direct[k], 1e-12 * std::max(1.0, direct[k]))
                << "size " << size << " level " << k;
        }
    }
}

TEST(ImageErrorMetric, KnownValues) {
    // A checkerboard of ±1 differences: RMS 1 at full resolution, 0 at every coarser
    // level (each 2×2 block averages to zero).
    const int size = 16;
    std::vector<float> a(size * size), zero(size * size, 0.0f);
    for (int y = 0; y < size; ++y) {
        for (int x = 0; x < size; ++x) {
            a[y * size + x] = (x + y) % 2 ? 1.0f : -1.0f;
        }
    }
    const auto levels = multiScaleSquaredErrors(a, zero, size);
    EXPECT_DOUBLE_EQ(levels[0], 1.0);
    for (std::size_t k = 1; k < levels.size(); ++k) {
        EXPECT_DOUBLE_EQ(levels[k], 0.0);
    }
    EXPECT_DOUBLE_EQ(multiScaleRmse(levels), 1.0 / 5.0);
    // A constant offset counts equally on every level.
    std::vector<float> half(size * size, 0.5f);
    for (double e : multiScaleSquaredErrors(half, zero, size)) {
        EXPECT_DOUBLE_EQ(e, 0.25);
    }
}

}  // namespace
}  // namespace sylva
