#include "sylva/core/image/RankFilter.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <random>

namespace sylva {
namespace {

// The direct definition (MaskSource's filter before van Herk / Gil-Werman): per texel the
// extremum of its 2r+1 neighbours along x, then along y, edges clamped; values in [0, 1].
void directRank(std::vector<float>& grid, int width, int r, bool dilate) {
    std::vector<float> tmp(grid.size());
    for (int pass = 0; pass < 2; ++pass) {
        for (int y = 0; y < width; ++y) {
            for (int x = 0; x < width; ++x) {
                float v = dilate ? 0.0f : 1.0f;
                for (int d = -r; d <= r; ++d) {
                    const int xx = std::clamp(pass == 0 ? x + d : x, 0, width - 1);
                    const int yy = std::clamp(pass == 0 ? y : y + d, 0, width - 1);
                    const float s = grid[std::size_t(yy) * width + xx];
                    v = dilate ? std::max(v, s) : std::min(v, s);
                }
                tmp[std::size_t(y) * width + x] = v;
            }
        }
        grid.swap(tmp);
    }
}

// A mask-like grid: blobs of 1 in 0 with a few fractional texels (a feathered edge).
std::vector<float> maskGrid(int width, unsigned seed) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    std::vector<float> grid(std::size_t(width) * width);
    for (float& v : grid) {
        const float u = unit(random);
        v = u < 0.45f ? 0.0f : (u < 0.9f ? 1.0f : unit(random));
    }
    return grid;
}

TEST(RankFilter, EqualsTheDirectDefinitionBitForBit) {
    // Radii from one texel to beyond the grid (the clamped edges then fill whole lines),
    // window lengths that do and do not divide the padded line, odd and even widths.
    for (const int width : {1, 2, 7, 16, 33, 64}) {
        for (const int r : {1, 2, 3, 5, 8, 15, 40, 70}) {
            for (const bool dilate : {false, true}) {
                std::vector<float> expected = maskGrid(width, unsigned(width * 131 + r));
                std::vector<float> actual = expected;
                directRank(expected, width, r, dilate);
                RankFilter::apply(actual, width, r, dilate);
                ASSERT_EQ(
                    0, std::memcmp(expected.data(), actual.data(), expected.size() * sizeof(float)))
                    << "width " << width << ", r " << r << (dilate ? ", dilate" : ", erode");
            }
        }
    }
}

TEST(RankFilter, OpeningRemovesSpecksNarrowerThanTheElementAndKeepsWideAreas) {
    // An opening (erode then dilate) of radius 2 removes a 3x3 speck and keeps a 9x9
    // square exactly.
    const int width = 32;
    std::vector<float> grid(std::size_t(width) * width, 0.0f);
    const auto fill = [&](int x0, int y0, int size) {
        for (int y = y0; y < y0 + size; ++y) {
            for (int x = x0; x < x0 + size; ++x) {
                grid[std::size_t(y) * width + x] = 1.0f;
            }
        }
    };
    fill(3, 3, 3);
    fill(15, 12, 9);
    std::vector<float> square(grid.size(), 0.0f);
    square.swap(grid);
    fill(15, 12, 9);
    square.swap(grid);
    RankFilter::apply(grid, width, 2, false);
    RankFilter::apply(grid, width, 2, true);
    EXPECT_EQ(grid, square);
}

TEST(RankFilter, ZeroRadiusLeavesTheGrid) {
    std::vector<float> grid = maskGrid(9, 3);
    const std::vector<float> before = grid;
    RankFilter::apply(grid, 9, 0, true);
    EXPECT_EQ(grid, before);
}

}  // namespace
}  // namespace sylva
