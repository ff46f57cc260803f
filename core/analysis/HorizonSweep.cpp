#include "sylva/core/analysis/HorizonSweep.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "SightLine.h"

namespace sylva {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Linear interpolation of two horizons; −inf (no crossing) does not mix.
double blendHorizons(double a, double b, double f) {
    if (f == 0.0)
        return a;
    if (std::isinf(a) || std::isinf(b))
        return std::max(a, b);
    return a * (1.0 - f) + b * f;
}

class Sweep {
    // The propagated horizon of a cell: the estimate (linear interpolation behind) and
    // the bounds (min and max behind); all three equal where the cell was exact.
    struct Horizon {
        double estimate = -kInfinity, low = -kInfinity, high = -kInfinity;
    };

public:
    Sweep(const ElevationGrid& grid, const HorizonSweepInput& input, HorizonSweepResult& result)
        : grid_(grid),
          input_(input),
          result_(result),
          width_(grid.geometry.width),
          height_(grid.geometry.height),
          nearCol_(int(std::lround(input.col))),
          nearRow_(int(std::lround(input.row))) {}

    void run() {
        const std::size_t cells = std::size_t(width_) * std::size_t(height_);
        result_.horizon.assign(cells, float(-kInfinity));
        low_.assign(cells, float(-kInfinity));
        high_.assign(cells, float(-kInfinity));
        result_.visible.assign(cells, 0);
        visit(nearCol_, nearRow_, 0);
        const int rings =
            std::max({nearCol_, width_ - 1 - nearCol_, nearRow_, height_ - 1 - nearRow_});
        for (int k = 1; k <= rings; ++k)
            visitRing(k);
    }

private:
    // The sides of ring k first (they depend on ring k − 1 only), then its corners.
    void visitRing(int k) {
        for (int c = nearCol_ - k + 1; c <= nearCol_ + k - 1; ++c) {
            visit(c, nearRow_ - k, k);
            visit(c, nearRow_ + k, k);
        }
        for (int r = nearRow_ - k + 1; r <= nearRow_ + k - 1; ++r) {
            visit(nearCol_ - k, r, k);
            visit(nearCol_ + k, r, k);
        }
        visit(nearCol_ - k, nearRow_ - k, k);
        visit(nearCol_ + k, nearRow_ - k, k);
        visit(nearCol_ - k, nearRow_ + k, k);
        visit(nearCol_ + k, nearRow_ + k, k);
    }

    double distance(double dc, double dr) const {
        const double x = dc * grid_.geometry.cellWidth, y = dr * grid_.geometry.cellHeight;
        return std::sqrt(x * x + y * y);  // not hypot: no overflow here, and 10× cheaper
    }

    void visit(int col, int row, int ring) {
        if (col < 0 || row < 0 || col >= width_ || row >= height_)
            return;
        const std::size_t i = std::size_t(row) * std::size_t(width_) + std::size_t(col);
        const double dc = col - input_.col, dr = row - input_.row;
        const double length = distance(dc, dr);
        Horizon horizon;
        if (ring <= 2)
            horizon.estimate = horizon.low = horizon.high = exactHorizon(grid_, input_, col, row);
        else
            horizon = propagated(col, row, dc, dr, length);
        const float z = (input_.eyeGround != nullptr ? *input_.eyeGround : grid_).at(col, row);
        if (!std::isnan(z) && length > 0.0) {
            const double rise =
                z + input_.observerHeight - length * length * input_.sagFactor - input_.top;
            // Decided when the eye clears the high bound or stays under the low one by
            // the margin; otherwise (and always with an infinite margin) exactly.
            const double m = input_.refineMargin;
            if (ring > 2 && rise < horizon.high * length + m && rise >= horizon.low * length - m) {
                horizon.estimate = horizon.low = horizon.high =
                    exactHorizon(grid_, input_, col, row);
                ++result_.refinedCells;
            }
            result_.visible[i] = rise - horizon.high * length >= 0.0 ? 1 : 0;
        } else if (!std::isnan(z)) {
            result_.visible[i] = 1;  // the viewpoint stands on this cell's centre
        }
        result_.horizon[i] = float(horizon.estimate);
        low_[i] = float(horizon.low);
        high_[i] = float(horizon.high);
    }

    // Height of the grid line `line` (a column when `columns`) at `across`, linear
    // between its two cell centres (NaN: no data).
    double lineHeight(bool columns, int line, double across) const {
        const int acrossLast = columns ? height_ - 1 : width_ - 1;
        const double clamped = std::clamp(across, 0.0, double(acrossLast));
        const int a0 = std::min(int(clamped), std::max(acrossLast - 1, 0));
        const int a1 = std::min(a0 + 1, acrossLast);
        const double f = clamped - a0;
        return grid_.heights[cellIndex(columns, line, a0)] * (1.0 - f) +
               grid_.heights[cellIndex(columns, line, a1)] * f;
    }

    std::size_t cellIndex(bool columns, int line, int across) const {
        return columns ? std::size_t(across) * std::size_t(width_) + std::size_t(line)
                       : std::size_t(line) * std::size_t(width_) + std::size_t(across);
    }

    double slopeAt(double z, double d) const {
        return (z - d * d * input_.sagFactor - input_.top) / d;
    }

    // H(c): the exact crossings of the last `lookback` lines of the ray's dominant axis
    // (and the crossings of the other axis's lines in between), then the horizon of
    // the line reached, interpolated between its two cells.
    Horizon propagated(int col, int row, double dc, double dr, double length) const {
        const bool columns = std::abs(dc) >= std::abs(dr);
        const double along = columns ? dc : dr, acrossSpan = columns ? dr : dc;
        const double alongFrom = columns ? input_.col : input_.row;
        const double acrossFrom = columns ? input_.row : input_.col;
        const int step = along > 0.0 ? 1 : -1;
        const int here = columns ? col : row;
        // Lines strictly beyond the viewpoint: |here − j·step − from| > 0.
        const int reach = int(std::ceil(std::abs(along))) - 1;
        const int back = std::min(input_.lookback, reach);
        double best = -kInfinity;
        double across = 0.0;
        for (int j = 1; j <= back; ++j) {
            const int line = here - j * step;
            const double t = (line - alongFrom) / along;
            across = acrossFrom + acrossSpan * t;
            const double z = lineHeight(columns, line, across);
            if (!std::isnan(z))
                best = std::max(best, slopeAt(z, t * length));
        }
        // The other axis's lines strictly between the last line reached and the cell.
        const double acrossHere = columns ? row : col;
        const int lo = int(std::floor(std::min(across, acrossHere))) + 1;
        const int hi = int(std::ceil(std::max(across, acrossHere))) - 1;
        for (int k = lo; k <= hi; ++k) {
            const double t = (k - acrossFrom) / acrossSpan;
            const double z = lineHeight(!columns, k, alongFrom + along * t);
            if (!std::isnan(z))
                best = std::max(best, slopeAt(z, t * length));
        }
        // The horizon behind the last line, between its two cells.
        const int line = here - back * step;
        const int acrossLast = columns ? height_ - 1 : width_ - 1;
        const double clamped = std::clamp(across, 0.0, double(acrossLast));
        const int a0 = std::min(int(clamped), std::max(acrossLast - 1, 0));
        const int a1 = std::min(a0 + 1, acrossLast);
        const std::size_t i0 = cellIndex(columns, line, a0), i1 = cellIndex(columns, line, a1);
        const double f = clamped - a0;
        Horizon out;
        out.estimate = std::max(best, blendHorizons(result_.horizon[i0], result_.horizon[i1], f));
        // Bounds: the horizon behind lies between those of the two cells (their bounds).
        out.low = std::max(best, double(f == 0.0 ? low_[i0] : std::min(low_[i0], low_[i1])));
        out.high = std::max(best, double(f == 0.0 ? high_[i0] : std::max(high_[i0], high_[i1])));
        return out;
    }

    std::vector<float> low_, high_;
    const ElevationGrid& grid_;
    const HorizonSweepInput& input_;
    HorizonSweepResult& result_;
    int width_, height_;
    int nearCol_, nearRow_;  // the cell nearest the viewpoint: ring 0
};

}  // namespace

double exactHorizon(const ElevationGrid& grid, const HorizonSweepInput& input, int col, int row) {
    SightLine line;
    line.fromCol = input.col;
    line.fromRow = input.row;
    line.toCol = col;
    line.toRow = row;
    line.length = std::hypot((col - input.col) * grid.geometry.cellWidth,
                             (row - input.row) * grid.geometry.cellHeight);
    line.start = input.top;
    line.sagFactor = input.sagFactor;
    if (line.length == 0.0)
        return -kInfinity;
    return maxCrossingSlope(grid, line);
}

HorizonSweepResult sweepHorizons(const ElevationGrid& grid, const HorizonSweepInput& input) {
    HorizonSweepResult result;
    Sweep(grid, input, result).run();
    return result;
}

}  // namespace sylva
