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

Result<double> ElevationQuery::heightAt(double latitude, double longitude, int level,
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
    Result<TilePointer> tile =
        provider_.tile(elevation_, TileKey{level, lonReduction, tileX, tileY});
    if (!tile) {
        return tile.error();
    }
    // Position inside the tile; the border supplies neighbours across tile edges.
    const double fx = x - double(tileX) * size - 0.5;
    const double fy = y - double(tileY) * size - 0.5;
    const int ix = static_cast<int>(std::floor(fx));
    const int iy = static_cast<int>(std::floor(fy));
    const double tx = fx - ix, ty = fy - iy;
    const ImageTile& t = *tile.value();
    const double top = t.at(ix, iy, 0) * (1 - tx) + t.at(ix + 1, iy, 0) * tx;
    const double bottom = t.at(ix, iy + 1, 0) * (1 - tx) + t.at(ix + 1, iy + 1, 0) * tx;
    return top * (1 - ty) + bottom * ty;
}

Result<double> ElevationQuery::groundHeight(double latitude, double longitude,
                                            int ringLevel) const {
    const ClipmapWindow window =
        Clipmap::windowFor(ringLevel, latitude, longitude, provider_.format().size);
    return heightAt(latitude, longitude, window.level, window.lonReduction);
}

}  // namespace sylva
