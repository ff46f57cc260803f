// TileEvaluator: the synchronous TileProvider. Looks tiles up in one TileCache per
// source content hash (so equal sources of different scenarios share tiles) and
// produces missing ones depth-first through the source graph.
//
// The concurrent manager/worker Scheduler (seed 001 §4.6-4.7) will implement the
// same TileProvider interface; callers do not change.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <unordered_map>

#include "sylva/core/sources/Source.h"
#include "sylva/core/tiles/TileCache.h"

namespace sylva {

struct TileStatistics {
    std::size_t hits = 0;
    std::size_t misses = 0;     // tiles produced
    std::size_t failures = 0;   // distinct failed tiles
    double produceSeconds = 0;  // wall time of top-level produce calls (inputs included once)
};

class TileEvaluator final : public TileProvider {
public:
    explicit TileEvaluator(TileFormat format = {}, std::size_t budgetBytesPerSource = 512u << 20);

    // The tile, from cache or produced now. A failed tile is produced once; later
    // requests return the same error without retrying.
    Result<TilePointer> tile(const Source& source, const TileKey& key) override;
    const TileFormat& format() const override { return format_; }

    const TileStatistics& statistics() const { return statistics_; }
    std::size_t cachedBytes() const;
    // Drops every cached tile (and remembered failure) of sources with this hash.
    void invalidate(std::uint64_t contentHash);

private:
    TileFormat format_;
    std::size_t budgetBytesPerSource_;
    std::unordered_map<std::uint64_t, TileCache> caches_;
    std::map<std::pair<std::uint64_t, TileKey>, Error> failures_;
    TileStatistics statistics_;
    int depth_ = 0;  // recursion depth: only top-level calls are timed
};

}  // namespace sylva
