// The bare-earth viewshed against analytic limits: curvature and refraction on a flat
// grid (just both sides of the horizon limit), a ridge's geometric shadow, cumulative
// counts and the visible share of a target's height.
#include "sylva/core/analysis/Viewshed.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace sylva {
namespace {

ElevationGrid flatGrid(int width, int height, double cell, float z = 0.0f) {
    ElevationGrid grid;
    grid.geometry = {1000.0, 5000.0, cell, cell, width, height};
    grid.heights.assign(std::size_t(width) * std::size_t(height), z);
    return grid;
}

ViewshedTarget targetAt(const ElevationGrid& grid, double col, double row, double height) {
    return {grid.geometry.centreX(col), grid.geometry.centreY(row), height};
}

// Flat Earth surface, observer eye h above it at distance d from a target: the line of
// sight grazes the sphere (radius R/(1 − k)) when the target is (d − √(2R'h))² / (2R')
// high (d beyond the eye's horizon).
double horizonLimit(double d, double eye, const ViewshedOptions& o) {
    const double r = o.earthRadius / (1.0 - o.refraction);
    const double horizon = std::sqrt(2.0 * r * eye);
    return (d - horizon) * (d - horizon) / (2.0 * r);
}

TEST(Viewshed, CurvatureAndRefractionLimitOnFlatGround) {
    const ElevationGrid grid = flatGrid(3001, 1, 10.0, 5.0f);
    for (const double k : {0.0, 0.13}) {
        for (const double eye : {2.0, 10.0}) {
            ViewshedOptions options;
            options.observerHeight = eye;
            options.refraction = k;
            const double d = 20000.0;  // 2000 cells
            const double limit = horizonLimit(d, eye, options);
            ASSERT_GT(limit, 1.0);
            const ViewshedTarget below = targetAt(grid, 2000, 0, limit - 0.01);
            const ViewshedTarget above = targetAt(grid, 2000, 0, limit + 0.01);
            EXPECT_GT(lowestVisibleHeight(grid, 0, 0, below, options), below.height)
                << "k " << k << " eye " << eye << " limit " << limit;
            EXPECT_LE(lowestVisibleHeight(grid, 0, 0, above, options), above.height)
                << "k " << k << " eye " << eye << " limit " << limit;
            EXPECT_NEAR(lowestVisibleHeight(grid, 0, 0, above, options), limit, 1e-3);
        }
    }
    // Without curvature flat ground never hides anything.
    ViewshedOptions flat;
    flat.curvature = false;
    EXPECT_LT(lowestVisibleHeight(grid, 0, 0, targetAt(grid, 3000, 0, 0.5), flat), 0.0);
}

TEST(Viewshed, WholeGridCurvatureLimitMatchesFormula) {
    const ElevationGrid grid = flatGrid(1601, 1, 25.0);
    ViewshedOptions options;
    options.observerHeight = 2.0;
    const ViewshedTarget target = targetAt(grid, 0, 0, 20.0);
    auto result = computeViewshed(grid, std::span(&target, 1), options);
    ASSERT_TRUE(result.ok()) << result.error().message;
    int checked = 0;
    for (int col = 1; col < grid.geometry.width; ++col) {
        const double limit = horizonLimit(col * 25.0, options.observerHeight, options);
        const double margin = target.height - limit;
        if (std::abs(margin) < 0.01)
            continue;  // on the boundary: either answer
        EXPECT_EQ(result->visible[std::size_t(col)], margin > 0.0 ? 1 : 0) << "col " << col;
        ++checked;
    }
    EXPECT_GT(checked, 1500);
    EXPECT_GT(result->visibleCells(), 100u);
    EXPECT_LT(result->visibleCells(), 1600u);
}

// A one-cell ridge of height hr along column cr on flat ground (no curvature): a cell at
// column c beyond it sees a target top at column t < cr exactly when the sight line
// passes over the ridge crest, h_o + (H − h_o)·(c − cr)/(c − t) ≥ hr, whatever the rows.
TEST(Viewshed, RidgeHidesExactlyItsGeometricShadow) {
    const int size = 120, ridge = 40;
    const double hr = 30.0, eye = 2.0, height = 80.0;
    ElevationGrid grid = flatGrid(size, size, 10.0);
    for (int row = 0; row < size; ++row)
        grid.heights[std::size_t(row) * size + ridge] = float(hr);
    ViewshedOptions options;
    options.observerHeight = eye;
    options.curvature = false;
    const double tc = 20.0, tr = 57.3;
    const ViewshedTarget target = targetAt(grid, tc, tr, height);
    auto result = computeViewshed(grid, std::span(&target, 1), options);
    ASSERT_TRUE(result.ok()) << result.error().message;
    int hidden = 0, mismatches = 0;
    for (int row = 0; row < size; ++row) {
        for (int col = 0; col < size; ++col) {
            bool visible = true;
            if (col > ridge) {
                const double s = (col - ridge) / (col - tc);
                visible = eye + (height - eye) * s >= hr;
            }
            hidden += visible ? 0 : 1;
            const bool got = result->visible[std::size_t(row) * size + col] == 1;
            if (got != visible)
                ++mismatches;
            EXPECT_EQ(got, visible) << "col " << col << " row " << row;
            if (mismatches > 5)
                return;
        }
    }
    // The analytic shadow starts at c = (hr·... ) and is a band of whole columns.
    EXPECT_GT(hidden, 10 * size);
    EXPECT_LT(hidden, (size - ridge - 1) * size);
}

TEST(Viewshed, FractionOfHeightBehindARidge) {
    // Observer at column 100, ridge crest at column 50 (hr), target at column 0: the
    // lowest visible point is where the line from the eye over the crest meets the
    // target: eye + (hr − eye)·2.
    const int width = 101;
    ElevationGrid grid = flatGrid(width, 1, 10.0);
    grid.heights[50] = 20.0f;
    ViewshedOptions options;
    options.curvature = false;
    options.observerHeight = 2.0;
    const double lowest = 2.0 + (20.0 - 2.0) * 2.0;  // 38 m
    const ViewshedTarget target = targetAt(grid, 0, 0, 100.0);
    EXPECT_NEAR(lowestVisibleHeight(grid, 100, 0, target, options), lowest, 1e-9);
    auto result = computeViewshed(grid, std::span(&target, 1), options);
    ASSERT_TRUE(result.ok());
    EXPECT_NEAR(result->fraction[100], (100.0 - lowest) / 100.0, 1e-6);
    EXPECT_FLOAT_EQ(result->fraction[10], 1.0f);  // in front of the ridge: all of it
}

TEST(Viewshed, CumulativeCountsTargets) {
    const int width = 101;
    ElevationGrid grid = flatGrid(width, 1, 10.0);
    grid.heights[50] = 20.0f;
    ViewshedOptions options;
    options.curvature = false;
    // A tall target left (seen over the ridge from the right side), a short one left
    // (hidden from the right side), one on the right (seen everywhere on the right).
    const std::vector<ViewshedTarget> targets = {
        targetAt(grid, 0, 0, 100.0), targetAt(grid, 0, 0, 5.0), targetAt(grid, 100, 0, 5.0)};
    auto result = computeViewshed(grid, targets, options);
    ASSERT_TRUE(result.ok());
    EXPECT_EQ(result->count[10], 2);  // left side: both left targets; the right one is hidden
    EXPECT_EQ(result->count[90], 2);  // right side: the tall left one and the right one
    EXPECT_EQ(result->visible[90], 1);
}

TEST(Viewshed, BadInputsAreErrors) {
    const ElevationGrid grid = flatGrid(10, 10, 10.0);
    ViewshedOptions options;
    ViewshedTarget outside{0.0, 0.0, 10.0};
    auto r1 = computeViewshed(grid, std::span(&outside, 1), options);
    ASSERT_FALSE(r1.ok());
    EXPECT_EQ(r1.error().message, "target 1: lies outside the analysis grid");
    ViewshedTarget flat = targetAt(grid, 5, 5, 0.0);
    auto r2 = computeViewshed(grid, std::span(&flat, 1), options);
    ASSERT_FALSE(r2.ok());
    EXPECT_EQ(r2.error().message, "target 1: the height must be positive");
    ViewshedTarget good = targetAt(grid, 5, 5, 10.0);
    options.refraction = 1.0;
    EXPECT_FALSE(computeViewshed(grid, std::span(&good, 1), options).ok());
    options.refraction = 0.13;
    options.observerHeight = -1.0;
    EXPECT_FALSE(computeViewshed(grid, std::span(&good, 1), options).ok());
}

}  // namespace
}  // namespace sylva
