// TileCache: the tiles of one source, keyed by TileKey, bounded by a byte budget.
// Eviction is least-recently-used for now; pruning by distance to the clipmap focus
// (seed 001 Fig. 4.3a) replaces it when the concurrent scheduler lands.
// Not thread-safe: the owner (TileEvaluator) serialises access.
#pragma once

#include <cstddef>
#include <list>
#include <unordered_map>

#include "sylva/core/tiles/TileProvider.h"

namespace sylva {

class TileCache {
public:
    explicit TileCache(std::size_t budgetBytes) : budgetBytes_(budgetBytes) {}

    // nullptr when absent. Marks the tile as recently used.
    TilePointer find(const TileKey& key);
    // Inserts (or replaces) and evicts least-recently-used tiles beyond the budget;
    // the tile just inserted is never evicted.
    void insert(const TileKey& key, TilePointer tile);
    void clear();

    std::size_t bytes() const { return bytes_; }
    std::size_t size() const { return entries_.size(); }
    std::size_t evictions() const { return evictions_; }

private:
    struct Entry {
        TilePointer tile;
        std::list<TileKey>::iterator recency;
    };
    std::size_t budgetBytes_;
    std::size_t bytes_ = 0;
    std::size_t evictions_ = 0;
    std::list<TileKey> recency_;  // front: most recent
    std::unordered_map<TileKey, Entry, TileKeyHash> entries_;
};

}  // namespace sylva
