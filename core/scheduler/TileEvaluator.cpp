#include "sylva/core/scheduler/TileEvaluator.h"

#include <chrono>

namespace sylva {

TileEvaluator::TileEvaluator(TileFormat format, std::size_t budgetBytesPerSource)
    : format_(format), budgetBytesPerSource_(budgetBytesPerSource) {}

Result<TilePointer> TileEvaluator::tile(const Source& source, const TileKey& key) {
    SYLVA_CHECK_MESSAGE(key.valid(), "TileEvaluator::tile: invalid tile key");
    const std::uint64_t hash = source.contentHash();
    auto cacheIt = caches_.try_emplace(hash, budgetBytesPerSource_).first;
    if (TilePointer cached = cacheIt->second.find(key)) {
        ++statistics_.hits;
        return cached;
    }
    if (auto failed = failures_.find({hash, key}); failed != failures_.end()) {
        return failed->second;
    }
    ++statistics_.misses;
    ++depth_;
    const auto start = std::chrono::steady_clock::now();
    Result<TilePointer> produced = source.produce(key, *this);
    if (depth_ == 1) {  // inputs produced meanwhile are part of this call's time
        statistics_.produceSeconds +=
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
    --depth_;
    if (!produced) {
        ++statistics_.failures;
        Error error{"source '" + source.name() + "', tile " + key.toString() + ": " +
                    produced.error().message};
        failures_.emplace(std::make_pair(hash, key), error);
        return error;
    }
    SYLVA_CHECK(produced.value() != nullptr);
    SYLVA_CHECK(produced.value()->key() == key);
    caches_.find(hash)->second.insert(key, produced.value());
    return produced;
}

std::size_t TileEvaluator::cachedBytes() const {
    std::size_t total = 0;
    for (const auto& [hash, cache] : caches_) {
        total += cache.bytes();
    }
    return total;
}

void TileEvaluator::invalidate(std::uint64_t contentHash) {
    caches_.erase(contentHash);
    for (auto it = failures_.begin(); it != failures_.end();) {
        it = it->first.first == contentHash ? failures_.erase(it) : std::next(it);
    }
}

}  // namespace sylva
