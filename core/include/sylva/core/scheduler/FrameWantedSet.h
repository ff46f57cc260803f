// FrameWantedSet: one interactive frame's wanted tiles from every client, handed to the
// Scheduler as one list (seed 001 Algorithm 3, "cancel previous tile tasks; enqueue
// taskList", with every renderer of the frame contributing to the one task list).
//
// A frame has several clients of the tile provider: the terrain's clipmaps, the
// far-field canopy's clipmaps (a second TerrainRenderer), the vegetation stream's
// instance tiles and the nadir elevation probe. When each called the Scheduler's
// setWanted itself, the later list cancelled the queued tasks of the earlier one every
// frame (docs/architecture.md, far-field "Interactive use"), and the queue was rebuilt in
// a different order each frame. This decorator sits between the clients and the
// provider for one frame: setWanted lists and the tiles still pending after a tryGet are
// merged (one entry per source content hash and key, the smallest priority wins), and
// flush() hands the merged list to the provider's setWanted once. Priorities are the
// clients' "screen importance" on one scale: a tile's priority is the ring level whose
// ring covers it (coarse first: a coarse level covers most of the screen), plus a small
// offset per kind (terrain 0, instance tiles 0 at their own distance, canopy +1), so
// instance tiles near the camera come before far terrain detail and are never starved.
//
// Everything else (tile, format, setFocus, waitForProgress, tryGet's answer) goes
// straight to the wrapped provider. Not thread-safe: the render thread's, for one frame.
#pragma once

#include <cstdint>
#include <map>
#include <utility>
#include <vector>

#include "sylva/core/sources/Source.h"
#include "sylva/core/tiles/TileProvider.h"

namespace sylva {

class FrameWantedSet final : public TileProvider {
public:
    // `provider` must outlive this object.
    explicit FrameWantedSet(TileProvider& provider) : provider_(provider) {}

    Result<TilePointer> tile(const Source& source, const TileKey& key) override {
        return provider_.tile(source, key);
    }
    const TileFormat& format() const override { return provider_.format(); }
    // The provider's answer; a tile still pending joins the frame's wanted list.
    TileLookup tryGet(const Source& source, const TileKey& key, int priority) override;
    // Merged into the frame's list instead of replacing it.
    void setWanted(const std::vector<TileRequest>& wanted) override;
    void setFocus(double latitude, double longitude) override {
        provider_.setFocus(latitude, longitude);
    }
    void waitForProgress(std::chrono::milliseconds timeout) override {
        provider_.waitForProgress(timeout);
    }

    // The merged list, most urgent first (priority, then the order first asked for).
    std::vector<TileRequest> requests() const;
    // Hands requests() to the provider's setWanted (once per frame) and starts a new list.
    void flush();

private:
    void add(const TileRequest& request);

    TileProvider& provider_;
    // (content hash, key) -> the request and the order it was first added in.
    std::map<std::pair<std::uint64_t, TileKey>, std::pair<TileRequest, std::size_t>> wanted_;
};

}  // namespace sylva
