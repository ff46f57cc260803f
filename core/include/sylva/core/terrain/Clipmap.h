// Clipmap: the CPU side of one clipmap layer (height, colour or normals), seed 001
// §4.3.1 and §4.5. Each level is a size x size texel window of one grid of the tile
// pyramid around the focus, stored with toroidal addressing: global texel (gx, gy)
// lives at (gx mod size, gy mod size), so moving the focus only rewrites the strips
// that entered the window. Tiles are as large as the window, so a window touches at
// most a 2 x 2 quad of tiles and one update splits into at most nine regions (Fig.
// 4.3b). The renderer uploads exactly the regions reported by takeDirtyRegions().
//
// Level i of the clipmap belongs to ring level i of the spherical geometry clipmap
// (seed 001 §5.3.4: ring i covers view angles (2^-(i+1) pi, 2^-i pi]); its window
// uses pyramid level max(0, i - levelOffset) and the coarsest longitude reduction
// that still covers the ring (§5.4.1: the longitude range grows towards the poles,
// in power-of-two steps). With levelOffset 2 (height) a window spans twice the
// ring's radius; with levelOffset 1 (colour and normals at twice the resolution, as
// seed 001 §4.8.2 gives colour more texels than height) it spans the radius itself,
// which suffices: a ring gives its own level zero weight in its outer tenth
// (TerrainRings blends fully to the coarser level there).
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "sylva/core/base/Result.h"
#include "sylva/core/sources/Source.h"

namespace sylva {

// The window of one clipmap level in the global texel grid of pyramid level `level`
// with longitude reduction `lonReduction`. Rows may extend beyond the poles (those
// texels repeat the nearest pole row); columns wrap around the globe.
struct ClipmapWindow {
    std::int32_t level = 0;
    std::int32_t lonReduction = 0;
    std::int64_t originX = 0;  // first global column, in [0, totalColumns)
    std::int64_t originY = 0;  // first global row (may be negative near the north pole)

    std::int64_t totalColumns(int size) const {
        return std::int64_t{TileKey::columns(level, lonReduction)} * size;
    }
    std::int64_t totalRows(int size) const { return std::int64_t{TileKey::rows(level)} * size; }
    double texelWidth(int size) const;   // radians of longitude
    double texelHeight(int size) const;  // radians of latitude
    friend bool operator==(const ClipmapWindow&, const ClipmapWindow&) = default;
};

class Clipmap {
public:
    struct Region {
        int level = 0;
        int x = 0, y = 0;  // texel rectangle in the level's (toroidal) texture, no wrap inside
        int width = 0, height = 0;
    };
    using Fetch = std::function<Result<TilePointer>(const TileKey&)>;

    Clipmap(int levelCount, int size, int channels);

    // The window that clipmap level `level` needs for a focus at (latitude,
    // longitude) in radians. Deterministic; equal inputs give equal windows.
    static ClipmapWindow windowFor(int level, double latitude, double longitude, int size,
                                   int levelOffset = 2);
    // The tiles a full update of `window` reads (at most a 2 x 2 quad, fewer where rows
    // beyond a pole repeat the pole row): a superset of what any update to it fetches,
    // so a renderer can request them ahead (seed 001 §4.5.1, the quad).
    static std::vector<TileKey> tilesFor(const ClipmapWindow& window, int size);
    // Ring radius of level i in radians of view angle: 2^-i pi.
    static double ringRadius(int level);

    // Brings `level` to `window`, copying only texels that are not already in place
    // (all of them when the grid changed or the window moved by a full size). On a
    // fetch error the level becomes invalid and the error is returned.
    Status update(int level, const ClipmapWindow& window, const Fetch& fetch);
    void invalidate(int level);

    std::vector<Region> takeDirtyRegions();

    int levelCount() const { return static_cast<int>(levels_.size()); }
    int size() const { return size_; }
    int channels() const { return channels_; }
    bool valid(int level) const { return levels_.at(level).window.has_value(); }
    const ClipmapWindow& window(int level) const;
    // size * size * channels floats, row-major in texture coordinates.
    const std::vector<float>& data(int level) const { return levels_.at(level).texels; }
    // Texel value at a global coordinate inside the level's window.
    float texel(int level, std::int64_t globalX, std::int64_t globalY, int channel) const;

    std::uint64_t texelsCopied() const { return texelsCopied_; }

private:
    struct Level {
        std::optional<ClipmapWindow> window;
        std::vector<float> texels;
    };
    Status copyRect(int level, const ClipmapWindow& window, std::int64_t x0, std::int64_t y0,
                    std::int64_t x1, std::int64_t y1, const Fetch& fetch);

    int size_;
    int channels_;
    std::vector<Level> levels_;
    std::vector<Region> dirty_;
    std::uint64_t texelsCopied_ = 0;
};

}  // namespace sylva
