#include "sylva/core/analysis/Viewshed.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "SightLine.h"
#include "sylva/core/analysis/HorizonSweep.h"
#include "sylva/core/base/WorkerPool.h"

namespace sylva {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

Status checkInputs(const ElevationGrid& grid, std::span<const ViewshedTarget> targets,
                   const ViewshedOptions& options) {
    SYLVA_CHECK(grid.heights.size() ==
                std::size_t(grid.geometry.width) * std::size_t(grid.geometry.height));
    if (grid.geometry.width < 1 || grid.geometry.height < 1)
        return Error{"the grid is empty"};
    if (!(options.observerHeight >= 0.0))
        return Error{"the observer height must not be negative"};
    if (!(options.refraction >= 0.0 && options.refraction < 1.0))
        return Error{"the refraction coefficient must lie in [0, 1)"};
    if (!(options.refineMargin >= 0.0))
        return Error{"the refinement margin must not be negative"};
    if (!(options.earthRadius > 0.0))
        return Error{"the Earth radius must be positive"};
    if (targets.size() > 65535)
        return Error{"at most 65535 targets"};
    for (std::size_t i = 0; i < targets.size(); ++i) {
        const ViewshedTarget& t = targets[i];
        const std::string name = "target " + std::to_string(i + 1);
        if (!(t.height > 0.0))
            return Error{name + ": the height must be positive"};
        if (!grid.geometry.containsCentreHull(t.x, t.y))
            return Error{name + ": lies outside the analysis grid"};
        if (std::isnan(grid.interpolate(grid.geometry.colOf(t.x), grid.geometry.rowOf(t.y))))
            return Error{name + ": stands on no-data terrain"};
    }
    return Status::success();
}

double sagFactorOf(const ViewshedOptions& options) {
    return options.curvature ? (1.0 - options.refraction) / (2.0 * options.earthRadius) : 0.0;
}

}  // namespace

std::size_t ViewshedResult::visibleCells() const {
    return std::size_t(std::count(visible.begin(), visible.end(), std::uint8_t(1)));
}

double lowestVisibleHeight(const ElevationGrid& grid, int col, int row,
                           const ViewshedTarget& target, const ViewshedOptions& options) {
    return lowestVisibleHeight(grid, grid, col, row, target, options);
}

double lowestVisibleHeight(const ElevationGrid& surface, const ElevationGrid& ground, int col,
                           int row, const ViewshedTarget& target, const ViewshedOptions& options) {
    const GridGeometry& g = surface.geometry;
    SightLine line;
    line.fromCol = col;
    line.fromRow = row;
    line.toCol = g.colOf(target.x);
    line.toRow = g.rowOf(target.y);
    line.length = std::hypot((line.toCol - col) * g.cellWidth, (line.toRow - row) * g.cellHeight);
    line.start = ground.at(col, row) + options.observerHeight;
    line.sagFactor = sagFactorOf(options);
    const double foot = ground.interpolate(line.toCol, line.toRow);
    if (line.length == 0.0)
        return -kInfinity;  // the target stands in the observer's cell
    const double slope = maxCrossingSlope(surface, line);
    if (slope == -kInfinity)
        return -kInfinity;
    // Target elevation needed (curved frame of the eye), back to height above ground.
    const double sag = line.length * line.length * line.sagFactor;
    return line.start + slope * line.length + sag - foot;
}

bool insideScreen(const ElevationGrid& ground, const ElevationGrid& surface, std::size_t cell,
                  double observerHeight) {
    return &ground != &surface && surface.heights[cell] - ground.heights[cell] >= observerHeight;
}

namespace {

// The terrain of one computation: sight lines over `surface`, eyes and feet on `ground`
// (the same grid for the bare-earth ZTV).
struct Terrain {
    const ElevationGrid& ground;
    const ElevationGrid& surface;

    // No observer here: no data, or inside a screen.
    bool noObserver(std::size_t i, const ViewshedOptions& options) const {
        return std::isnan(ground.heights[i]) ||
               insideScreen(ground, surface, i, options.observerHeight);
    }
};

// The exact method: every cell's line of sight to every target (R3), rows in parallel.
void exactViewshed(const Terrain& terrain, std::span<const ViewshedTarget> targets,
                   const ViewshedOptions& options, ViewshedResult& result) {
    const GridGeometry& g = terrain.ground.geometry;
    WorkerPool::shared().run(g.height, [&](int row) {
        for (int col = 0; col < g.width; ++col) {
            const std::size_t i = std::size_t(row) * std::size_t(g.width) + std::size_t(col);
            if (terrain.noObserver(i, options))
                continue;
            int count = 0;
            double fraction = 0.0;
            for (const ViewshedTarget& target : targets) {
                const double lowest =
                    lowestVisibleHeight(terrain.surface, terrain.ground, col, row, target, options);
                if (lowest > target.height)
                    continue;
                ++count;
                fraction = std::max(fraction,
                                    std::clamp((target.height - lowest) / target.height, 0.0, 1.0));
            }
            result.visible[i] = count > 0 ? 1 : 0;
            result.count[i] = std::uint16_t(count);
            result.fraction[i] = options.fraction ? float(fraction) : 0.0f;
        }
    });
}

// The sweep method, one target: the sweep from the top decides visibility; with
// fractions, a sweep from the foot finds the cells seen down to the ground (1) and R3
// gives the lowest visible point of the rest of the visible cells.
void sweepTarget(const Terrain& terrain, const ViewshedTarget& target,
                 const ViewshedOptions& options, ViewshedResult& result) {
    const GridGeometry& g = terrain.ground.geometry;
    HorizonSweepInput input;
    input.col = g.colOf(target.x);
    input.row = g.rowOf(target.y);
    input.sagFactor = sagFactorOf(options);
    input.observerHeight = options.observerHeight;
    input.refineMargin = options.refineMargin;
    input.eyeGround = &terrain.ground;
    const double foot = terrain.ground.interpolate(input.col, input.row);
    HorizonSweepResult top, base;
    WorkerPool::shared().run(options.fraction ? 2 : 1, [&](int which) {
        HorizonSweepInput in = input;
        in.top = foot + (which == 0 ? target.height : 0.0);
        (which == 0 ? top : base) = sweepHorizons(terrain.surface, in);
    });
    WorkerPool::shared().run(g.height, [&](int row) {
        for (int col = 0; col < g.width; ++col) {
            const std::size_t i = std::size_t(row) * std::size_t(g.width) + std::size_t(col);
            if (top.visible[i] == 0 || terrain.noObserver(i, options))
                continue;
            result.visible[i] = 1;
            ++result.count[i];
            if (!options.fraction)
                continue;
            double fraction = 1.0;
            if (base.visible[i] == 0) {
                const double lowest =
                    lowestVisibleHeight(terrain.surface, terrain.ground, col, row, target, options);
                fraction = std::clamp((target.height - lowest) / target.height, 0.0, 1.0);
            }
            result.fraction[i] = std::max(result.fraction[i], float(fraction));
        }
    });
}

}  // namespace

Result<ViewshedResult> computeViewshed(const ElevationGrid& grid,
                                       std::span<const ViewshedTarget> targets,
                                       const ViewshedOptions& options) {
    return computeViewshed(grid, grid, targets, options);
}

Result<ViewshedResult> computeViewshed(const ElevationGrid& ground, const ElevationGrid& surface,
                                       std::span<const ViewshedTarget> targets,
                                       const ViewshedOptions& options) {
    if (Status ok = checkInputs(ground, targets, options); !ok)
        return ok.error();
    const GridGeometry& g = ground.geometry;
    const GridGeometry& s = surface.geometry;
    if (s.width != g.width || s.height != g.height || s.originX != g.originX ||
        s.originY != g.originY || s.cellWidth != g.cellWidth || s.cellHeight != g.cellHeight ||
        surface.heights.size() != ground.heights.size())
        return Error{"the screened surface does not have the ground's grid"};
    const std::size_t cells = std::size_t(g.width) * std::size_t(g.height);
    ViewshedResult result;
    result.geometry = g;
    result.visible.assign(cells, 0);
    result.count.assign(cells, 0);
    result.fraction.assign(cells, 0.0f);
    const Terrain terrain{ground, surface};
    if (options.method == ViewshedMethod::Exact) {
        exactViewshed(terrain, targets, options, result);
    } else {
        for (const ViewshedTarget& target : targets)
            sweepTarget(terrain, target, options, result);
    }
    for (std::size_t i = 0; i < cells; ++i)
        if (terrain.noObserver(i, options))
            result.fraction[i] = std::numeric_limits<float>::quiet_NaN();
    return result;
}

}  // namespace sylva
