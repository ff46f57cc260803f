// TileProvider: how sources obtain the tiles of their inputs, and how renderers ask for
// the tiles of a frame (seed 001 §4.6). The tile layer knows sources only as opaque keys
// (a `Source` is declared, not defined, here): implementations that produce tiles (the
// TileEvaluator and the Scheduler, in core/scheduler) come after the sources in the
// pipeline and include sources/Source.h themselves.
#pragma once

#include <chrono>
#include <memory>
#include <vector>

#include "sylva/core/base/Result.h"
#include "sylva/core/tiles/ImageTile.h"
#include "sylva/core/tiles/TileKey.h"

namespace sylva {

class Source;
using TilePointer = std::shared_ptr<const ImageTile>;

// Texels per tile side and border width shared by every tile of one graph.
struct TileFormat {
    int size = 256;
    int border = 2;
};

// One wanted tile: the source, the key and a priority (smaller runs first).
struct TileRequest {
    const Source* source = nullptr;
    TileKey key;
    int priority = 0;
};

// The answer of TileProvider::tryGet(): a ready tile, "pending" (queued or being
// produced), or the remembered error of a failed tile.
struct TileLookup {
    enum class State { Ready, Pending, Failed };
    State state = State::Pending;
    TilePointer tile;  // Ready only
    Error error;       // Failed only
};

// Gives a source the tiles of its inputs. Implementations cache and may compute
// in parallel; produce() only calls tile() for its own inputs.
//
// Renderers use the non-blocking part: tryGet(), setWanted() (the tiles the current
// frame needs; queued work for others is cancelled), setFocus() (the pruning centre)
// and waitForProgress(). A synchronous provider (TileEvaluator) answers tryGet() by
// producing the tile at once and ignores the rest, so the same renderer code works
// with both.
class TileProvider {
public:
    virtual ~TileProvider() = default;
    virtual Result<TilePointer> tile(const Source& source, const TileKey& key) = 0;
    virtual const TileFormat& format() const = 0;

    virtual TileLookup tryGet(const Source& source, const TileKey& key, int priority);
    virtual void setWanted(const std::vector<TileRequest>& wanted) { (void)wanted; }
    virtual void setFocus(double latitude, double longitude) { (void)latitude, (void)longitude; }
    // Blocks until a tile finished or `timeout` passed (returns at once if nothing runs).
    virtual void waitForProgress(std::chrono::milliseconds timeout) { (void)timeout; }
};

}  // namespace sylva
