#include "SightLine.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sylva {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// The crossings with the grid lines `index = const` of one axis (column lines: x).
double maxSlopeOverLines(const ElevationGrid& grid, const SightLine& line, bool columnLines) {
    const double from = columnLines ? line.fromCol : line.fromRow;
    const double to = columnLines ? line.toCol : line.toRow;
    const double span = to - from;
    if (span == 0.0)
        return -kInfinity;
    const double acrossFrom = columnLines ? line.fromRow : line.fromCol;
    const double acrossSpan = (columnLines ? line.toRow : line.toCol) - acrossFrom;
    const int last = columnLines ? grid.geometry.width - 1 : grid.geometry.height - 1;
    const int acrossLast = columnLines ? grid.geometry.height - 1 : grid.geometry.width - 1;
    const int step = span > 0.0 ? 1 : -1;
    // Lines strictly between: index in the open interval (from, to).
    const int first = span > 0.0 ? int(std::floor(from)) + 1 : int(std::ceil(from)) - 1;
    const int end = span > 0.0 ? int(std::ceil(to)) : int(std::floor(to));
    double best = -kInfinity;
    for (int k = first; k != end; k += step) {
        if (k < 0 || k > last)
            break;
        const double s = (k - from) / span;  // 0..1 along the line
        const double across = std::clamp(acrossFrom + s * acrossSpan, 0.0, double(acrossLast));
        const int a0 = std::min(int(across), std::max(acrossLast - 1, 0));
        const int a1 = std::min(a0 + 1, acrossLast);
        const double f = across - a0;
        const float z0 = columnLines ? grid.at(k, a0) : grid.at(a0, k);
        const float z1 = columnLines ? grid.at(k, a1) : grid.at(a1, k);
        const double z = z0 * (1.0 - f) + z1 * f;
        if (std::isnan(z))
            continue;
        const double d = s * line.length;
        const double slope = (z - d * d * line.sagFactor - line.start) / d;
        best = std::max(best, slope);
    }
    return best;
}

}  // namespace

double maxCrossingSlope(const ElevationGrid& grid, const SightLine& line) {
    return std::max(maxSlopeOverLines(grid, line, true), maxSlopeOverLines(grid, line, false));
}

}  // namespace sylva
