#include "sylva/core/terrain/LevelVisibility.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "sylva/core/geo/Ellipsoid.h"

namespace sylva {

double LevelVisibility::horizonViewAngle(double heightAboveEllipsoid, double maxTerrainHeight) {
    const double r = Ellipsoid::kMeanRadius;
    const double h = std::max(heightAboveEllipsoid, 1.0);
    const double angle =
        std::acos(r / (r + h)) + std::acos(r / (r + std::max(maxTerrainHeight, 0.0)));
    return std::min(angle, std::numbers::pi / 2);
}

double LevelVisibility::pixelViewAngle(double heightAboveTerrain, double verticalFov, int pixels) {
    const double s =
        std::max(heightAboveTerrain, 0.01) * 2.0 * std::tan(verticalFov / 2) / std::max(pixels, 1);
    return s / Ellipsoid::kMeanRadius;
}

LevelRange LevelVisibility::visibleLevels(double heightAboveEllipsoid, double heightAboveTerrain,
                                          double maxTerrainHeight, double verticalFov, int pixels,
                                          int maxLevel) {
    const double pi = std::numbers::pi;
    LevelRange range;
    // Level i's outer border is 2^-i pi: the coarsest level must reach the horizon.
    const double horizon = horizonViewAngle(heightAboveEllipsoid, maxTerrainHeight);
    range.coarsest = std::clamp(static_cast<int>(std::floor(std::log2(pi / horizon))), 1, maxLevel);
    // The finest level's inner border 2^-(i+1) pi must get below theta_min.
    const double smallest = pixelViewAngle(heightAboveTerrain, verticalFov, pixels);
    const int finest = static_cast<int>(std::ceil(std::log2(pi / smallest))) - 1;
    range.finest = std::clamp(finest, range.coarsest, maxLevel);
    return range;
}

}  // namespace sylva
