// GroundSampler: terrain heights under footprints and placements (buildings, objects,
// elevation_edit `level`), bilinear between the
// texel centres of one pyramid level of an elevation source (the same filter as
// ElevationQuery::heightAt and the GPU's, at MeshSource::kGroundLevel). Keeps the last
// tile, since a footprint's samples almost always fall into one. Not thread-safe: one
// sampler per tile production.
#pragma once

#include "sylva/core/sources/Source.h"

namespace sylva {

class GroundSampler {
public:
    GroundSampler(const Source& elevation, TileProvider& provider, int level);

    // Height in metres above the ellipsoid at (latitude, longitude) radians; fails when the
    // elevation tile cannot be produced (the message names the source and tile).
    Result<double> heightAt(double latitude, double longitude);

private:
    const Source& elevation_;
    TileProvider& provider_;
    int level_;
    TileKey lastKey_{-1, 0, 0, 0};
    TilePointer lastTile_;
};

}  // namespace sylva
