#include "sylva/core/analysis/Viewshed.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "sylva/core/base/WorkerPool.h"

namespace sylva {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// One ray from an observer cell centre (oc, orow) to the target (tc, tr), in grid
// coordinates; distances in metres.
struct Ray {
    double oc, orow, tc, tr;
    double length;     // horizontal metres from eye to target
    double eye;        // eye elevation, metres
    double sagFactor;  // (1 − k) / (2R), 1/m; 0 without curvature
};

// Largest (terrain − eye) / distance over the crossings of the ray with the grid lines
// `index = const` of one axis, strictly between observer and target. `along` is the
// axis the lines cross (column lines: x), `across` the other one.
double maxSlopeOverLines(const ElevationGrid& grid, const Ray& ray, bool columnLines) {
    const double from = columnLines ? ray.oc : ray.orow;
    const double to = columnLines ? ray.tc : ray.tr;
    const double span = to - from;
    if (span == 0.0)
        return -kInfinity;
    const double acrossFrom = columnLines ? ray.orow : ray.oc;
    const double acrossSpan = (columnLines ? ray.tr : ray.tc) - acrossFrom;
    const int last = columnLines ? grid.geometry.width - 1 : grid.geometry.height - 1;
    const int acrossLast = columnLines ? grid.geometry.height - 1 : grid.geometry.width - 1;
    const int step = span > 0.0 ? 1 : -1;
    const int first = int(from) + step;
    // Lines strictly between: k in (from, to) open.
    const int end = span > 0.0 ? int(std::ceil(to)) : int(std::floor(to));
    double best = -kInfinity;
    for (int k = first; k != end; k += step) {
        if (k < 0 || k > last)
            break;
        const double s = (k - from) / span;  // 0..1 along the ray
        const double across = std::clamp(acrossFrom + s * acrossSpan, 0.0, double(acrossLast));
        const int a0 = std::min(int(across), std::max(acrossLast - 1, 0));
        const int a1 = std::min(a0 + 1, acrossLast);
        const double f = across - a0;
        const float z0 = columnLines ? grid.at(k, a0) : grid.at(a0, k);
        const float z1 = columnLines ? grid.at(k, a1) : grid.at(a1, k);
        const double z = z0 * (1.0 - f) + z1 * f;
        if (std::isnan(z))
            continue;
        const double d = s * ray.length;
        const double slope = (z - d * d * ray.sagFactor - ray.eye) / d;
        best = std::max(best, slope);
    }
    return best;
}

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

}  // namespace

std::size_t ViewshedResult::visibleCells() const {
    return std::size_t(std::count(visible.begin(), visible.end(), std::uint8_t(1)));
}

double lowestVisibleHeight(const ElevationGrid& grid, int col, int row,
                           const ViewshedTarget& target, const ViewshedOptions& options) {
    const GridGeometry& g = grid.geometry;
    Ray ray;
    ray.oc = col;
    ray.orow = row;
    ray.tc = g.colOf(target.x);
    ray.tr = g.rowOf(target.y);
    ray.length = std::hypot((ray.tc - ray.oc) * g.cellWidth, (ray.tr - ray.orow) * g.cellHeight);
    ray.eye = grid.at(col, row) + options.observerHeight;
    ray.sagFactor =
        options.curvature ? (1.0 - options.refraction) / (2.0 * options.earthRadius) : 0.0;
    const double ground = grid.interpolate(ray.tc, ray.tr);
    if (ray.length == 0.0)
        return -kInfinity;  // the target stands in the observer's cell
    const double slope =
        std::max(maxSlopeOverLines(grid, ray, true), maxSlopeOverLines(grid, ray, false));
    if (slope == -kInfinity)
        return -kInfinity;
    // Target elevation needed (curved frame of the eye), back to height above ground.
    const double sag = ray.length * ray.length * ray.sagFactor;
    return ray.eye + slope * ray.length + sag - ground;
}

Result<ViewshedResult> computeViewshed(const ElevationGrid& grid,
                                       std::span<const ViewshedTarget> targets,
                                       const ViewshedOptions& options) {
    if (Status ok = checkInputs(grid, targets, options); !ok)
        return ok.error();
    const GridGeometry& g = grid.geometry;
    const std::size_t cells = std::size_t(g.width) * std::size_t(g.height);
    ViewshedResult result;
    result.geometry = g;
    result.visible.assign(cells, 0);
    result.count.assign(cells, 0);
    result.fraction.assign(cells, 0.0f);
    WorkerPool::shared().run(g.height, [&](int row) {
        for (int col = 0; col < g.width; ++col) {
            const std::size_t i = std::size_t(row) * std::size_t(g.width) + std::size_t(col);
            if (std::isnan(grid.at(col, row))) {
                result.fraction[i] = std::numeric_limits<float>::quiet_NaN();
                continue;
            }
            int count = 0;
            double fraction = 0.0;
            for (const ViewshedTarget& target : targets) {
                const double lowest = lowestVisibleHeight(grid, col, row, target, options);
                if (lowest > target.height)
                    continue;
                ++count;
                fraction = std::max(fraction,
                                    std::clamp((target.height - lowest) / target.height, 0.0, 1.0));
            }
            result.visible[i] = count > 0 ? 1 : 0;
            result.count[i] = std::uint16_t(count);
            result.fraction[i] = float(fraction);
        }
    });
    return result;
}

}  // namespace sylva
