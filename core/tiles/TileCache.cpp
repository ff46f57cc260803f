#include "sylva/core/tiles/TileCache.h"

namespace sylva {

TilePointer TileCache::find(const TileKey& key) {
    auto it = entries_.find(key);
    if (it == entries_.end()) {
        return nullptr;
    }
    recency_.splice(recency_.begin(), recency_, it->second.recency);
    return it->second.tile;
}

void TileCache::insert(const TileKey& key, TilePointer tile) {
    SYLVA_CHECK(tile != nullptr);
    auto it = entries_.find(key);
    if (it != entries_.end()) {
        bytes_ -= it->second.tile->bytes();
        recency_.erase(it->second.recency);
        entries_.erase(it);
    }
    bytes_ += tile->bytes();
    recency_.push_front(key);
    entries_.emplace(key, Entry{std::move(tile), recency_.begin()});
    while (bytes_ > budgetBytes_ && entries_.size() > 1) {
        const TileKey oldest = recency_.back();
        auto victim = entries_.find(oldest);
        bytes_ -= victim->second.tile->bytes();
        entries_.erase(victim);
        recency_.pop_back();
        ++evictions_;
    }
}

void TileCache::clear() {
    entries_.clear();
    recency_.clear();
    bytes_ = 0;
}

}  // namespace sylva
