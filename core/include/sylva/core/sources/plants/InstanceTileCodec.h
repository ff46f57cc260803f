// InstanceTileCodec: plant instances carried in an ImageTile, so that instance tiles
// travel through the same Scheduler as raster tiles (deduplicated, prioritised,
// cancelled, cached under the shared memory budget, failures reported once) — the
// instance streaming of the vegetation renderer (issue 7) needs nothing of its own.
//
// Layout: a square tile without border, four floats per texel. Texel 0 holds the
// instance count (exact as a float up to 2^24); the twelve floats of texels 1 + 3i to
// 3 + 3i hold instance i: the raw
// bits of longitude, latitude and height (doubles, two 32-bit words each), the species
// index (raw bits), scale, rotation and tint. The words are copied, never computed
// with, so the round trip is bit-exact.
#pragma once

#include <vector>

#include "sylva/core/base/Result.h"
#include "sylva/core/sources/plants/InstanceTile.h"
#include "sylva/core/tiles/ImageTile.h"

namespace sylva {

class InstanceTileCodec {
public:
    static constexpr int kChannels = 4;
    static constexpr int kFloatsPerInstance = 12;
    static constexpr std::size_t kMaximumInstances = 1u << 24;

    static ImageTile encode(const TileKey& key, const std::vector<PlantInstance>& instances);
    // Fails when the tile does not have the codec's layout.
    static Result<std::vector<PlantInstance>> decode(const ImageTile& tile);
};

}  // namespace sylva
