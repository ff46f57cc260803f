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
// Units: grid coordinates (integers are cell centres), metres, radians. No-data ground
// does not block. Thread safety: const methods may be called from many threads.
#pragma once

#include <cstdint>
#include <vector>

#include "sylva/core/analysis/ElevationGrid.h"

namespace sylva {

class ShadowCaster {
public:
    // `screens`: metres above the ground per cell (row-major, the grid's size; 0 = none);
    // empty: bare earth. A mismatched size is a programmer error.
    ShadowCaster(const ElevationGrid& ground, std::vector<float> screens);

    // True when the point at (col, row) on the surface sees the sun.
    bool sunlit(double col, double row, double azimuth, double elevation) const;

    // 1 (lit) or 0 (shadow) per cell centre, rows in parallel (WorkerPool::shared()).
    std::vector<std::uint8_t> sunlitCells(double azimuth, double elevation) const;

    // The surface height at (col, row): ground (bilinear) + the screen of its cell.
    double surfaceAt(double col, double row) const;

    const ElevationGrid& ground() const { return ground_; }
    const std::vector<float>& screens() const { return screens_; }

private:
    double screenOfCell(int col, int row) const;

    const ElevationGrid& ground_;
    std::vector<float> screens_;
    double highest_ = 0.0;  // metres, the highest surface point
};

}  // namespace sylva
