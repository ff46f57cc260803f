#include "sylva/core/sources/GroundSampler.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace sylva {

GroundSampler::GroundSampler(const Source& elevation, TileProvider& provider, int level)
    : elevation_(elevation), provider_(provider), level_(level) {}

Result<double> GroundSampler::heightAt(double latitude, double longitude) {
    const double pi = std::numbers::pi;
    const int size = provider_.format().size;
    const int columns = TileKey::columns(level_, 0);
    const int rows = TileKey::rows(level_);
    const double texelWidth = 2 * pi / (double(columns) * size);
    const double texelHeight = pi / (double(rows) * size);
    // Continuous texel coordinates with texel centres at +0.5 (as ElevationQuery).
    double x = (longitude + pi) / texelWidth;
    x -= std::floor(x / (double(columns) * size)) * (double(columns) * size);
    const double y = std::clamp((pi / 2 - latitude) / texelHeight, 0.5, double(rows) * size - 0.5);
    const TileKey key{level_, 0, std::min(static_cast<int>(x / size), columns - 1),
                      std::min(static_cast<int>(y / size), rows - 1)};
    if (!lastTile_ || !(key == lastKey_)) {
        Result<TilePointer> tile = provider_.tile(elevation_, key);
        if (!tile) {
            return tile.error();
        }
        lastTile_ = tile.value();
        lastKey_ = key;
    }
    // Position inside the tile; the border supplies neighbours across tile edges.
    const double fx = x - double(key.x) * size - 0.5;
    const double fy = y - double(key.y) * size - 0.5;
    const int ix = static_cast<int>(std::floor(fx));
    const int iy = static_cast<int>(std::floor(fy));
    const double tx = fx - ix, ty = fy - iy;
    const ImageTile& t = *lastTile_;
    const double top = t.at(ix, iy, 0) * (1 - tx) + t.at(ix + 1, iy, 0) * tx;
    const double bottom = t.at(ix, iy + 1, 0) * (1 - tx) + t.at(ix + 1, iy + 1, 0) * tx;
    return top * (1 - ty) + bottom * ty;
}

}  // namespace sylva
