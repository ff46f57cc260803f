// ShadowCaster: direct sun or shadow on a surface model, by casting a ray from a point
// towards the sun (CPU ray marching; the shadow study's engine, docs/analysis.md).
//
// The surface: the bare earth of an ElevationGrid, bilinear between cell centres (as in
// the viewshed), plus screens (buildings, canopy; ScreeningSurface) as flat-topped
// prisms: a cell's screen raises the whole cell [col ± ½] × [row ± ½] by its height.
// A point lies on the surface: its height is the ground there plus its cell's screen.
// The ray leaves the point towards the sun (azimuth clockwise from north, elevation
// above the horizon, radians) and is tested where it crosses every line col = k/2 and
// row = k/2: the cell-centre lines, between which the ground is linear along the ray
// (R3's crossings), and the cell edges, where it enters a new prism (the prism's lowest
// point along a rising ray is its entry). The point is in shadow when the surface at
// a crossing lies strictly above the ray; the ray stops, lit, once it is higher than
// the highest surface point or leaves the grid. The sun is below the horizon when the
// elevation is ≤ 0 (shadow). Ground between crossings inside a cell can bulge above
// the linear interpolation by at most a quarter of the cell's twist (as for R3).
//
// The window: the cells whose sun sunlitCells reports (the study's grid inside a larger
// caster grid, so that ground and screens outside the study's extent still cast shadows
// into it); the whole grid by default.
//
// Units: grid coordinates (integers are cell centres), metres, radians. No-data ground
// does not block. Thread safety: const methods may be called from many threads.
#pragma once

#include <cstdint>
#include <vector>

#include "sylva/core/analysis/ElevationGrid.h"

namespace sylva {

// A block of cells of a grid: columns [col, col + width), rows [row, row + height).
struct CellWindow {
    int col = 0, row = 0;
    int width = 0, height = 0;
};

class ShadowCaster {
public:
    // `screens`: metres above the ground per cell (row-major, the grid's size; 0 = none);
    // empty: bare earth. `window`: the cells sunlitCells reports; width 0 = the whole
    // grid. A mismatched size or a window outside the grid is a programmer error.
    // `ground` is borrowed and must outlive the caster.
    ShadowCaster(const ElevationGrid& ground, std::vector<float> screens, CellWindow window = {});

    // True when the point at (col, row) of the whole grid on the surface sees the sun.
    bool sunlit(double col, double row, double azimuth, double elevation) const;

    // 1 (lit) or 0 (shadow) per cell centre of the window (row-major, the window's size),
    // rows in parallel (WorkerPool::shared()).
    std::vector<std::uint8_t> sunlitCells(double azimuth, double elevation) const;

    const CellWindow& window() const { return window_; }

    // The surface height at (col, row): ground (bilinear) + the screen of its cell.
    double surfaceAt(double col, double row) const;

    const ElevationGrid& ground() const { return ground_; }
    const std::vector<float>& screens() const { return screens_; }

private:
    double screenOfCell(int col, int row) const;

    const ElevationGrid& ground_;
    std::vector<float> screens_;
    CellWindow window_;
    double highest_ = 0.0;  // metres, the highest surface point
};

}  // namespace sylva
