// The horizon sweep against its oracle, the exact R3 line of sight (exactHorizon and
// ViewshedMethod::Exact): exact on axis and diagonal rays, equal to R3 everywhere with
// an infinite refinement margin, and equal in visibility, count and fraction with the
// default margin on synthetic rough terrain and the Olinda DEM (when present). Prints
// the propagated horizon's error in metres (docs/analysis.md quotes it).
#include "sylva/core/analysis/HorizonSweep.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <random>
#include <vector>

#include "sylva/core/analysis/Viewshed.h"

namespace sylva {
namespace {

// Rough terrain: a sum of random sine waves plus white noise, metres.
ElevationGrid roughGrid(int width, int height, double cell, unsigned seed) {
    ElevationGrid grid;
    grid.geometry = {500000.0, 7000000.0, cell, cell, width, height};
    grid.heights.resize(std::size_t(width) * std::size_t(height));
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    struct Wave {
        double kx, ky, phase, amplitude;
    };
    std::vector<Wave> waves;
    for (int i = 0; i < 12; ++i)
        waves.push_back(
            {(u(random) - 0.5) * 0.4, (u(random) - 0.5) * 0.4, u(random) * 6.28, 40.0 / (1.0 + i)});
    for (int r = 0; r < height; ++r)
        for (int c = 0; c < width; ++c) {
            double z = 100.0 + 3.0 * u(random);
            for (const Wave& w : waves)
                z += w.amplitude * std::sin(w.kx * c + w.ky * r + w.phase);
            grid.heights[std::size_t(r) * std::size_t(width) + std::size_t(c)] = float(z);
        }
    return grid;
}

HorizonSweepInput viewpointOn(const ElevationGrid& grid, double col, double row, double height) {
    HorizonSweepInput input;
    input.col = col;
    input.row = row;
    input.top = grid.interpolate(col, row) + height;
    input.sagFactor = (1.0 - 0.13) / (2.0 * 6371008.8);
    input.observerHeight = 2.0;
    return input;
}

struct ErrorFigures {
    double maxMetres = 0.0;  // largest |H_sweep − H_exact| · D, metres
    double p999 = 0.0;       // 99.9th percentile of the same
    std::size_t mismatches = 0;
};

// Propagated (no refinement) against exact horizons, cell by cell.
ErrorFigures propagationError(const ElevationGrid& grid, HorizonSweepInput input) {
    input.refineMargin = 0.0;
    const HorizonSweepResult sweep = sweepHorizons(grid, input);
    const GridGeometry& g = grid.geometry;
    std::vector<double> errors;
    ErrorFigures figures;
    for (int r = 0; r < g.height; ++r)
        for (int c = 0; c < g.width; ++c) {
            const std::size_t i = std::size_t(r) * std::size_t(g.width) + std::size_t(c);
            const double exact = exactHorizon(grid, input, c, r);
            const double d =
                std::hypot((c - input.col) * g.cellWidth, (r - input.row) * g.cellHeight);
            if (std::isinf(exact) || d == 0.0)
                continue;
            errors.push_back(std::abs(double(sweep.horizon[i]) - exact) * d);
            const double rise =
                grid.at(c, r) + input.observerHeight - d * d * input.sagFactor - input.top;
            figures.mismatches += (rise - exact * d >= 0.0) != (sweep.visible[i] == 1) ? 1 : 0;
        }
    std::sort(errors.begin(), errors.end());
    figures.maxMetres = errors.back();
    figures.p999 = errors[std::size_t(double(errors.size() - 1) * 0.999)];
    return figures;
}

TEST(HorizonSweep, ExactOnAxisAndDiagonalRays) {
    const ElevationGrid grid = roughGrid(61, 61, 10.0, 3);
    HorizonSweepInput input = viewpointOn(grid, 30, 30, 50.0);
    input.refineMargin = 0.0;
    const HorizonSweepResult sweep = sweepHorizons(grid, input);
    for (int k = -30; k <= 30; ++k) {
        for (const auto& [c, r] :
             {std::pair{30 + k, 30}, {30, 30 + k}, {30 + k, 30 + k}, {30 + k, 30 - k}}) {
            const double exact = exactHorizon(grid, input, c, r);
            const double got = sweep.horizon[std::size_t(r) * 61 + std::size_t(c)];
            EXPECT_TRUE(std::isinf(exact) ? std::isinf(got) : std::abs(got - exact) < 1e-6)
                << c << ", " << r << ": " << got << " vs " << exact;
        }
    }
}

TEST(HorizonSweep, InfiniteMarginIsExactEverywhere) {
    const ElevationGrid grid = roughGrid(80, 70, 20.0, 5);
    HorizonSweepInput input = viewpointOn(grid, 33.4, 41.7, 60.0);
    input.refineMargin = INFINITY;
    const HorizonSweepResult sweep = sweepHorizons(grid, input);
    for (int r = 0; r < 70; ++r)
        for (int c = 0; c < 80; ++c) {
            const double exact = exactHorizon(grid, input, c, r);
            const float got = sweep.horizon[std::size_t(r) * 80 + std::size_t(c)];
            if (std::isinf(exact))
                EXPECT_TRUE(std::isinf(got)) << c << ", " << r;
            else
                EXPECT_NEAR(got, exact, 1e-6 * std::max(1.0, std::abs(exact))) << c << ", " << r;
        }
}

// The propagated horizon's error on rough terrain, and no visibility mismatch left
// once the default margin sends the close calls to R3.
TEST(HorizonSweep, DefaultMarginMatchesExactOnRoughTerrain) {
    for (const unsigned seed : {1u, 2u, 7u}) {
        const ElevationGrid grid = roughGrid(181, 157, 30.0, seed);
        const HorizonSweepInput input = viewpointOn(grid, 60.0 + seed, 77.0, 100.0);
        const ErrorFigures figures = propagationError(grid, input);
        std::cout << "sweep horizon error, rough terrain seed " << seed << ": max "
                  << figures.maxMetres << " m, 99.9 % " << figures.p999
                  << " m, visibility mismatches without refinement " << figures.mismatches << " of "
                  << grid.heights.size() << "\n";
        const HorizonSweepResult refined = sweepHorizons(grid, input);
        std::size_t mismatches = 0;
        for (int r = 0; r < 157; ++r)
            for (int c = 0; c < 181; ++c) {
                const double exact = exactHorizon(grid, input, c, r);
                const double d = std::hypot((c - input.col) * 30.0, (r - input.row) * 30.0);
                const double rise =
                    grid.at(c, r) + input.observerHeight - d * d * input.sagFactor - input.top;
                const bool visible = d == 0.0 || rise - exact * d >= 0.0;
                mismatches +=
                    visible != (refined.visible[std::size_t(r) * 181 + std::size_t(c)] == 1);
            }
        std::cout << "  with the default margin: " << mismatches << " mismatches, "
                  << refined.refinedCells << " cells refined\n";
        EXPECT_LE(mismatches, grid.heights.size() / 2000)
            << "seed " << seed << ", refined " << refined.refinedCells;
        EXPECT_LE(mismatches, figures.mismatches) << "seed " << seed;
    }
}

// Sweep against Exact; `margin` +inf must agree everywhere, the default margin on all
// but `allowed` cells.
void expectSameViewshed(const ElevationGrid& grid, std::span<const ViewshedTarget> targets,
                        const std::string& tag, double margin, std::size_t allowed) {
    ViewshedOptions sweep, exact;
    sweep.refineMargin = margin;
    exact.method = ViewshedMethod::Exact;
    auto a = computeViewshed(grid, targets, sweep);
    auto b = computeViewshed(grid, targets, exact);
    ASSERT_TRUE(a.ok() && b.ok());
    std::size_t visible = 0, count = 0, fraction = 0;
    for (std::size_t i = 0; i < a->cells(); ++i) {
        visible += a->visible[i] != b->visible[i];
        count += a->count[i] != b->count[i];
        fraction += !(std::abs(a->fraction[i] - b->fraction[i]) <= 1e-5f) &&
                    !(std::isnan(a->fraction[i]) && std::isnan(b->fraction[i]));
    }
    std::cout << "sweep (margin " << margin << " m) vs exact [" << tag << "]: " << a->cells()
              << " cells, differing " << visible << " visible, " << count << " count, " << fraction
              << " fraction\n";
    EXPECT_LE(visible, allowed) << tag;
    EXPECT_LE(count, allowed) << tag;
    EXPECT_LE(fraction, allowed) << tag;
}

TEST(HorizonSweep, ViewshedEqualsExactMethod) {
    const ElevationGrid grid = roughGrid(120, 100, 25.0, 11);
    const GridGeometry& g = grid.geometry;
    const std::vector<ViewshedTarget> targets = {{g.centreX(20.3), g.centreY(70.8), 80.0},
                                                 {g.centreX(90), g.centreY(10), 150.0},
                                                 {g.centreX(60), g.centreY(50), 30.0}};
    expectSameViewshed(grid, targets, "rough, 3 targets", INFINITY, 0);
    expectSameViewshed(grid, targets, "rough, 3 targets", ViewshedOptions().refineMargin,
                       grid.heights.size() / 1000);
}

TEST(HorizonSweep, OlindaEqualsExactMethod) {
    const std::filesystem::path dem =
        std::filesystem::path(SYLVA_TEST_DATA_DIR) / "../data/olinda/olinda_dem_utm25s.tif";
    if (!std::filesystem::exists(dem))
        GTEST_SKIP() << "sample data absent; run scripts/fetch-samples";
    auto info = readRasterInfo(dem.string());
    ASSERT_TRUE(info.ok());
    GridGeometry g = info->geometry;
    g.width = int(g.width * g.cellWidth / 30.0);
    g.height = int(g.height * g.cellHeight / 30.0);
    g.cellWidth = g.cellHeight = 30.0;
    auto grid = readElevationGrid(dem.string(), g);
    ASSERT_TRUE(grid.ok());
    const HorizonSweepInput input = viewpointOn(*grid, 100, 120, 120.0);
    const ErrorFigures figures = propagationError(*grid, input);
    std::cout << "sweep horizon error, Olinda 30 m: max " << figures.maxMetres << " m, 99.9 % "
              << figures.p999 << " m, visibility mismatches without refinement "
              << figures.mismatches << " of " << grid->heights.size() << "\n";
    const std::vector<ViewshedTarget> targets = {{g.centreX(100), g.centreY(120), 120.0},
                                                 {g.centreX(250.5), g.centreY(40.2), 60.0}};
    expectSameViewshed(*grid, targets, "Olinda 30 m", INFINITY, 0);
    expectSameViewshed(*grid, targets, "Olinda 30 m", ViewshedOptions().refineMargin,
                       targets.size() * grid->heights.size() / 1000);
}

}  // namespace
}  // namespace sylva
