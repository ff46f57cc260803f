// HorizonSweep: the horizon slope of every cell seen from one viewpoint (a target's
// top or foot), by propagating horizons outwards ring by ring, with the exact R3 line
// of sight where the propagated value could decide wrongly. computeViewshed
// (Viewshed.h) uses it for ViewshedMethod::Sweep; public for the tests that measure it.
//
// Frame: the viewpoint V at fractional grid coordinates (col, row), elevation `top`
// (metres). Terrain at horizontal distance d from V sinks by d²·sagFactor (curvature
// and refraction; the sag is symmetric, so this frame gives the same answer as the
// eye's frame, docs/analysis.md). The horizon of cell c is
//     H(c) = max over the grid-line crossings x strictly between V and c of
//            (z(x) − d(x)²·sagFactor − top) / d(x),
// exactly the quantity R3 maximises. A point `eye` metres high over c is visible from
// V (and V from it) when (eye − D²·sagFactor − top) / D ≥ H(c), D = |c − V| in metres.
//
// Propagation (XDraw-like, Franklin & Ray 1994 "Higher isn't necessarily better",
// with R3's crossings): for a cell whose ray is closer to the x axis, the ray crosses
// the previous column at one point p, between two cells a, b of that column, and no
// row line between p and c. So
//     H(c) = max(H(p), slope of the crossing at p),
// the crossing's slope exactly (bilinear height at p), H(p) interpolated linearly
// between H(a) and H(b): the only approximation (exact for rays along the axes and
// diagonals through a cell-centred viewpoint). Cells within 2 rings of V take R3.
// Rings are processed outwards from V's nearest cell, corners of a ring last (they may
// depend on the same ring's sides).
//
// Refinement: a cell whose visibility margin (eye − D²·sagFactor − top − H·D, metres)
// is smaller in magnitude than `refineMargin` gets the exact R3 horizon (also passed on
// to the cells behind it). With refineMargin = +inf the result is R3 everywhere; the
// measured error of the propagated horizon (docs/analysis.md, HorizonSweepTest) sets
// the default.
//
// Cost: O(cells) plus the refined cells' ray lengths; serial (one viewpoint per call;
// computeViewshed runs viewpoints on the WorkerPool).
#pragma once

#include <cstdint>
#include <vector>

#include "sylva/core/analysis/ElevationGrid.h"

namespace sylva {

struct HorizonSweepInput {
    double col = 0.0, row = 0.0;  // viewpoint, fractional grid coordinates inside the grid
    double top = 0.0;             // viewpoint elevation, metres
    double sagFactor = 0.0;       // (1 − k) / (2R), 1/m
    double observerHeight = 2.0;  // metres above each cell: the eye whose visibility counts
    double refineMargin = 1.0;    // metres; see above
    int lookback = 8;             // lines crossed exactly before interpolating, >= 1
    // The ground the eyes stand on (same geometry; the bare earth under a screened
    // surface); null: the swept grid itself. Not owned.
    const ElevationGrid* eyeGround = nullptr;
};

struct HorizonSweepResult {
    std::vector<float> horizon;         // H per cell, row-major; −inf when no crossing
    std::vector<std::uint8_t> visible;  // 1 when the eye over the cell sees V
    std::size_t refinedCells = 0;       // cells that took the exact R3 horizon
};

HorizonSweepResult sweepHorizons(const ElevationGrid& grid, const HorizonSweepInput& input);

// The exact R3 horizon of cell (col, row) seen from the viewpoint (the oracle).
double exactHorizon(const ElevationGrid& grid, const HorizonSweepInput& input, int col, int row);

}  // namespace sylva
