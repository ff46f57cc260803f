#include "sylva/core/terrain/ElevationQuery.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "sylva/core/terrain/Clipmap.h"

namespace sylva {

ElevationQuery::ElevationQuery(const Source& elevation, TileProvider& provider)
    : elevation_(elevation), provider_(provider) {
    SYLVA_CHECK(elevation.output() == PortType::Elevation);
}

ElevationQuery::Cell ElevationQuery::cellAt(double latitude, double longitude, int level,
                                            int lonReduction) const {
    const double pi = std::numbers::pi;
    const int size = provider_.format().size;
    const int columns = TileKey::columns(level, lonReduction);
    const int rows = TileKey::rows(level);
    const double texelWidth = 2 * pi / (double(columns) * size);
    const double texelHeight = pi / (double(rows) * size);
    // Continuous texel coordinates with texel centres at +0.5.
    double x = (longitude + pi) / texelWidth;
    x -= std::floor(x / (double(columns) * size)) * (double(columns) * size);
    const double y = std::clamp((pi / 2 - latitude) / texelHeight, 0.5, double(rows) * size - 0.5);
    const auto tileX = std::min(static_cast<int>(x / size), columns - 1);
    const auto tileY = std::min(static_cast<int>(y / size), rows - 1);
    return {TileKey{level, lonReduction, tileX, tileY}, x - double(tileX) * size,
            y - double(tileY) * size};
}

double ElevationQuery::sample(const ImageTile& t, const Cell& cell) {
    // Position inside the tile; the border supplies neighbours across tile edges.
    const double fx = cell.x - 0.5;
    const double fy = cell.y - 0.5;
    const int ix = static_cast<int>(std::floor(fx));
    const int iy = static_cast<int>(std::floor(fy));
    const double tx = fx - ix, ty = fy - iy;
    const double top = t.at(ix, iy, 0) * (1 - tx) + t.at(ix + 1, iy, 0) * tx;
    const double bottom = t.at(ix, iy + 1, 0) * (1 - tx) + t.at(ix + 1, iy + 1, 0) * tx;
    return top * (1 - ty) + bottom * ty;
}

Result<double> ElevationQuery::heightAt(double latitude, double longitude, int level,
                                        int lonReduction) const {
    const Cell cell = cellAt(latitude, longitude, level, lonReduction);
    Result<TilePointer> tile = provider_.tile(elevation_, cell.key);
    if (!tile) {
        return tile.error();
    }
    return sample(*tile.value(), cell);
}

Result<std::optional<double>> ElevationQuery::readyGroundHeight(double latitude, double longitude,
                                                                int ringLevel, int priority) const {
    const ClipmapWindow window =
        Clipmap::windowFor(ringLevel, latitude, longitude, provider_.format().size);
    const Cell cell = cellAt(latitude, longitude, window.level, window.lonReduction);
    TileLookup lookup = provider_.tryGet(elevation_, cell.key, priority);
    if (lookup.state == TileLookup::State::Failed) {
        return lookup.error;
    }
    if (lookup.state == TileLookup::State::Pending) {
        return std::optional<double>();
    }
    return std::optional<double>(sample(*lookup.tile, cell));
}

Result<double> ElevationQuery::groundHeight(double latitude, double longitude,
                                            int ringLevel) const {
    const ClipmapWindow window =
        Clipmap::windowFor(ringLevel, latitude, longitude, provider_.format().size);
    return heightAt(latitude, longitude, window.level, window.lonReduction);
}

}  // namespace sylva
