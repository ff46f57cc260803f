#include "sylva/core/analysis/ShadowCaster.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "sylva/core/base/Check.h"
#include "sylva/core/base/WorkerPool.h"

namespace sylva {

namespace {

// Distance (metres along the ray) to the next line k/2 of one axis, from `position`
// (grid units) moving by `rate` grid units per metre; +inf when not moving.
double nextHalfLine(double position, double rate) {
    if (rate == 0.0)
        return std::numeric_limits<double>::infinity();
    const double twice = position * 2.0;
    const double next = rate > 0.0 ? std::floor(twice + 1e-9) + 1.0 : std::ceil(twice - 1e-9) - 1.0;
    return (next * 0.5 - position) / rate;
}

}  // namespace

ShadowCaster::ShadowCaster(const ElevationGrid& ground, std::vector<float> screens,
                           CellWindow window)
    : ground_(ground), screens_(std::move(screens)), window_(window) {
    SYLVA_CHECK(screens_.empty() || screens_.size() == ground_.heights.size());
    const GridGeometry& g = ground_.geometry;
    if (window_.width == 0)
        window_ = {0, 0, g.width, g.height};
    SYLVA_CHECK(window_.col >= 0 && window_.row >= 0 && window_.width > 0 && window_.height > 0 &&
                window_.col + window_.width <= g.width && window_.row + window_.height <= g.height);
    highest_ = -std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < ground_.heights.size(); ++i)
        if (!std::isnan(ground_.heights[i]))
            highest_ = std::max(highest_, double(ground_.heights[i]) +
                                              (screens_.empty() ? 0.0 : double(screens_[i])));
}

double ShadowCaster::screenOfCell(int col, int row) const {
    if (screens_.empty())
        return 0.0;
    const GridGeometry& g = ground_.geometry;
    col = std::clamp(col, 0, g.width - 1);
    row = std::clamp(row, 0, g.height - 1);
    return screens_[std::size_t(row) * std::size_t(g.width) + std::size_t(col)];
}

double ShadowCaster::surfaceAt(double col, double row) const {
    return ground_.interpolate(col, row) +
           screenOfCell(int(std::lround(col)), int(std::lround(row)));
}

bool ShadowCaster::sunlit(double col, double row, double azimuth, double elevation) const {
    if (!(elevation > 0.0))
        return false;
    const GridGeometry& g = ground_.geometry;
    const double rateCol = std::sin(azimuth) / g.cellWidth;    // grid units per metre
    const double rateRow = -std::cos(azimuth) / g.cellHeight;  // rows grow southwards
    const double rise = std::tan(elevation);
    const double start = surfaceAt(col, row);
    if (std::isnan(start))
        return true;
    double travelled = 0.0;
    double c = col, r = row;
    for (;;) {
        const double step = std::min(nextHalfLine(c, rateCol), nextHalfLine(r, rateRow));
        travelled += step;
        c = col + rateCol * travelled;
        r = row + rateRow * travelled;
        if (c < -0.5 || r < -0.5 || c > g.width - 0.5 || r > g.height - 0.5)
            return true;  // left the grid
        const double ray = start + rise * travelled;
        if (ray > highest_)
            return true;
        // The prism entered here: just beyond the crossing along the ray.
        const int cellCol = int(std::lround(c + rateCol * 1e-6));
        const int cellRow = int(std::lround(r + rateRow * 1e-6));
        const double surface = ground_.interpolate(c, r) + screenOfCell(cellCol, cellRow);
        if (surface > ray + 1e-9)
            return false;
    }
}

std::vector<std::uint8_t> ShadowCaster::sunlitCells(double azimuth, double elevation) const {
    const CellWindow& w = window_;
    std::vector<std::uint8_t> lit(std::size_t(w.width) * std::size_t(w.height), 0);
    if (!(elevation > 0.0))
        return lit;
    WorkerPool::shared().run(w.height, [&](int row) {
        for (int col = 0; col < w.width; ++col)
            lit[std::size_t(row) * std::size_t(w.width) + std::size_t(col)] =
                sunlit(w.col + col, w.row + row, azimuth, elevation) ? 1 : 0;
    });
    return lit;
}

}  // namespace sylva
