// Viewshed: the bare-earth zone of theoretical visibility (ZTV) of one or more targets
// on an ElevationGrid, by the exact line of sight from every cell (R3, see
// docs/analysis.md).
//
// Each target is a vertical segment from the ground at (x, y) (bilinear height of the
// grid) up to `height` metres above it (a turbine tip, a mast top). The observer stands
// at every cell centre with the eye `observerHeight` metres above the cell's height.
// The line of sight from the eye to a target point is tested against the terrain where
// it crosses the grid lines between cell centres (heights interpolated linearly along
// the grid line, i.e. the bilinear surface there); a crossing blocks when the terrain
// lies strictly above the line. Earth curvature and refraction: terrain and target sink
// by d²/(2R)·(1 − k) at horizontal distance d from the eye (R = earthRadius, default the
// IUGG mean Earth radius 6 371 008.8 m; k = refraction coefficient), which is symmetric
// in eye and target, so a cell sees the target exactly when the target sees the cell.
//
// Outputs per cell (row-major, the grid's geometry):
//   visible   1 when the top of at least one target is visible, else 0
//   count     number of targets whose top is visible (cumulative ZTV)
//   fraction  the largest visible share of a target's height over the targets, 0..1
//             (1: visible down to the ground; the part above the lowest visible point)
// No-data observer cells give 0, 0 and NaN; no-data cells along a ray do not block.
//
// Methods (ViewshedOptions::method): Exact tests every cell's line of sight (R3, cost
// O(cells × targets × ray length), rows on WorkerPool::shared()); Sweep (the default)
// propagates horizons outwards from each target (HorizonSweep, O(cells) per target)
// and takes R3 for the cells within `refineMargin` metres of their visibility limit
// and for the fraction of partly visible cells; docs/analysis.md gives its measured
// error against R3.
// Failures: a target outside the hull of the cell centres, a non-positive target
// height, a negative observer height or a bad refraction come back as Result errors.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "sylva/core/analysis/ElevationGrid.h"
#include "sylva/core/base/Result.h"

namespace sylva {

struct ViewshedTarget {
    double x = 0.0;       // CRS metres (the grid's CRS)
    double y = 0.0;       // CRS metres
    double height = 0.0;  // metres above the ground at (x, y), > 0
};

enum class ViewshedMethod { Sweep, Exact };

struct ViewshedOptions {
    double observerHeight = 2.0;     // metres above each cell, >= 0
    bool curvature = true;           // apply the d²/(2R)(1 − k) drop
    double refraction = 0.13;        // k, in [0, 1)
    double earthRadius = 6371008.8;  // metres (IUGG mean radius R1)
    ViewshedMethod method = ViewshedMethod::Sweep;
    // Sweep: cells whose propagated visibility margin is below this many metres take
    // the exact R3 line of sight (+inf: R3 everywhere). Metres, >= 0.
    double refineMargin = 1.0;
    // false: `fraction` is left at 0 (NaN on no-data), which saves the second sweep and
    // the R3 rays of partly visible cells (visibility-only ZTV, as gdal_viewshed).
    bool fraction = true;
};

struct ViewshedResult {
    GridGeometry geometry;
    std::vector<std::uint8_t> visible;
    std::vector<std::uint16_t> count;
    std::vector<float> fraction;

    std::size_t cells() const { return visible.size(); }
    std::size_t visibleCells() const;
};

// The lowest height above the target's ground (metres) at which the target is visible
// from the eye over cell (col, row); ≤ 0 when visible down to the ground, +inf never for
// finite terrain. The building block of computeViewshed, exposed for tests.
double lowestVisibleHeight(const ElevationGrid& grid, int col, int row,
                           const ViewshedTarget& target, const ViewshedOptions& options);
// The same over a screened surface: sight lines are blocked by `surface` (terrain plus
// screens), the eye and the target's foot stand on `ground` (same geometry).
double lowestVisibleHeight(const ElevationGrid& surface, const ElevationGrid& ground, int col,
                           int row, const ViewshedTarget& target, const ViewshedOptions& options);

Result<ViewshedResult> computeViewshed(const ElevationGrid& grid,
                                       std::span<const ViewshedTarget> targets,
                                       const ViewshedOptions& options);

// The screened ZTV: `surface` is the bare earth `ground` plus the screens (buildings,
// canopy; ScreeningSurface.h), same geometry. Observers and targets stand on the ground;
// sight lines are blocked by the surface. A cell whose screen is at least the observer
// height tall (inside a building or under a canopy higher than the eye) holds no
// observer: visible 0, count 0, fraction NaN, like no-data. A surface of another
// geometry is an error.
Result<ViewshedResult> computeViewshed(const ElevationGrid& ground, const ElevationGrid& surface,
                                       std::span<const ViewshedTarget> targets,
                                       const ViewshedOptions& options);

// True when the cell holds no observer in a screened ZTV (see above).
bool insideScreen(const ElevationGrid& ground, const ElevationGrid& surface, std::size_t cell,
                  double observerHeight);

}  // namespace sylva
