// SightLine: the grid-line crossings of one straight sight line over an ElevationGrid,
// the step shared by the exact R3 viewshed (Viewshed.cpp) and the horizon sweep
// (HorizonSweep.cpp). Private to core/analysis.
//
// A sight line runs horizontally from `from` (fractional grid coordinates, integers are
// cell centres) to `to`; its crossings with the lines col = const and row = const
// strictly between the two ends carry the terrain height interpolated linearly between
// the two cell centres on that grid line (Franklin & Ray's R3; the bilinear surface
// there). Distances are horizontal metres measured from `from`.
#pragma once

#include "sylva/core/analysis/ElevationGrid.h"

namespace sylva {

struct SightLine {
    double fromCol = 0.0, fromRow = 0.0;  // grid coordinates of the start (the viewpoint)
    double toCol = 0.0, toRow = 0.0;      // grid coordinates of the end
    double length = 0.0;                  // horizontal metres from start to end
    double start = 0.0;                   // elevation of the viewpoint, metres
    double sagFactor = 0.0;               // (1 − k) / (2R), 1/m; 0 without curvature
};

// Largest (terrain − start − sag) / distance over the crossings strictly between the
// ends, both families of grid lines; −inf when there is none. Terrain sinks by
// distance² · sagFactor (curvature and refraction seen from the start). No-data
// crossings are skipped (they do not block).
double maxCrossingSlope(const ElevationGrid& grid, const SightLine& line);

}  // namespace sylva
