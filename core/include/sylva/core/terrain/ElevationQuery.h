// ElevationQuery: the terrain height under a geographic point, from the same source
// and the same texel grid as the height clipmap, so cameras placed at an eye height
// stand where the GPU draws the ground (bilinear between texel centres, exactly as the
// GPU's linear filter does).
#pragma once

#include <optional>

#include "sylva/core/base/Result.h"
#include "sylva/core/sources/Source.h"

namespace sylva {

class ElevationQuery {
public:
    ElevationQuery(const Source& elevation, TileProvider& provider);

    // Height in metres at (latitude, longitude) radians, bilinear in the grid of
    // pyramid level `level` with longitude reduction `lonReduction`. Fails when the
    // tile cannot be produced (the message names source and tile).
    Result<double> heightAt(double latitude, double longitude, int level,
                            int lonReduction = 0) const;

    // Height in metres under (latitude, longitude) as ring level `ringLevel` of the
    // spherical clipmap draws it at the viewer's nadir: the same pyramid grid
    // (Clipmap::windowFor) and the same bilinear filter.
    Result<double> groundHeight(double latitude, double longitude, int ringLevel) const;

    // Non-blocking groundHeight (interactive frames, seed 001 §4.7: never wait for a
    // tile): the height when the tile is ready, nothing when it is still being produced
    // (it is then requested from the provider with `priority`), or the tile's error.
    Result<std::optional<double>> readyGroundHeight(double latitude, double longitude,
                                                    int ringLevel, int priority) const;

private:
    // The tile holding the texel neighbourhood of (latitude, longitude) at `level`, and
    // the bilinear sample of it.
    struct Cell {
        TileKey key;
        double x = 0;  // continuous texel coordinates inside the tile (centres at +0.5)
        double y = 0;
    };
    Cell cellAt(double latitude, double longitude, int level, int lonReduction) const;
    static double sample(const ImageTile& tile, const Cell& cell);

    const Source& elevation_;
    TileProvider& provider_;
};

}  // namespace sylva
