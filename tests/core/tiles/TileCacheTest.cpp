#include "sylva/core/tiles/TileCache.h"

#include <gtest/gtest.h>

#include "sylva/core/scheduler/TileEvaluator.h"

namespace sylva {
namespace {

TilePointer makeTile(const TileKey& key) {
    return std::make_shared<ImageTile>(key, 4, 0, 1);  // 16 floats = 64 bytes
}

TEST(TileCache, EvictsLeastRecentlyUsedBeyondBudget) {
    const TileKey a{2, 0, 0, 0}, b{2, 0, 1, 0}, c{2, 0, 2, 0}, d{2, 0, 3, 0};
    ASSERT_EQ(makeTile(a)->bytes(), 64u);
    TileCache cache(3 * 64);
    cache.insert(a, makeTile(a));
    cache.insert(b, makeTile(b));
    cache.insert(c, makeTile(c));
    EXPECT_EQ(cache.size(), 3u);
    EXPECT_EQ(cache.bytes(), 192u);
    EXPECT_EQ(cache.evictions(), 0u);

    ASSERT_NE(cache.find(a), nullptr);  // a is now the most recent; b the oldest
    cache.insert(d, makeTile(d));
    EXPECT_EQ(cache.size(), 3u);
    EXPECT_EQ(cache.bytes(), 192u);
    EXPECT_EQ(cache.evictions(), 1u);
    EXPECT_EQ(cache.find(b), nullptr);
    EXPECT_NE(cache.find(a), nullptr);
    EXPECT_NE(cache.find(c), nullptr);
    EXPECT_NE(cache.find(d), nullptr);
}

TEST(TileCache, ReplacingKeepsBytesAndLargeTileIsKept) {
    const TileKey a{1, 0, 0, 0};
    TileCache cache(100);
    cache.insert(a, makeTile(a));
    cache.insert(a, makeTile(a));
    EXPECT_EQ(cache.size(), 1u);
    EXPECT_EQ(cache.bytes(), 64u);
    // A tile larger than the whole budget evicts the others but stays itself.
    const TileKey big{1, 0, 1, 0};
    cache.insert(big, std::make_shared<ImageTile>(big, 8, 0, 1));
    EXPECT_EQ(cache.size(), 1u);
    EXPECT_NE(cache.find(big), nullptr);
    EXPECT_EQ(cache.find(a), nullptr);
    cache.clear();
    EXPECT_EQ(cache.size(), 0u);
    EXPECT_EQ(cache.bytes(), 0u);
}

// A source that counts produce() calls and can fail. `tag` goes into the content
// hash, so two instances with equal tags have equal content.
class CountingSource final : public Source {
public:
    CountingSource(std::string name, std::uint64_t tag, bool fail = false)
        : Source(std::move(name), "counting", PortType::Elevation, 1), fail_(fail) {
        setParameterHash(tag);
    }
    Result<TilePointer> produce(const TileKey& key, TileProvider& provider) const override {
        ++calls;
        if (fail_) {
            return Error{"disk on fire"};
        }
        auto tile =
            std::make_shared<ImageTile>(key, provider.format().size, provider.format().border, 1);
        for (float& t : tile->texels()) {
            t = float(key.x);
        }
        return TilePointer(std::move(tile));
    }
    mutable int calls = 0;

private:
    bool fail_;
};

TEST(TileEvaluator, SecondRequestIsACacheHit) {
    TileEvaluator evaluator(TileFormat{8, 1});
    CountingSource source("s", 1);
    const TileKey key{3, 0, 5, 2};
    Result<TilePointer> first = evaluator.tile(source, key);
    ASSERT_TRUE(first) << first.error().message;
    Result<TilePointer> second = evaluator.tile(source, key);
    ASSERT_TRUE(second);
    EXPECT_EQ(first.value(), second.value());
    EXPECT_EQ(source.calls, 1);
    EXPECT_EQ(evaluator.statistics().misses, 1u);
    EXPECT_EQ(evaluator.statistics().hits, 1u);
    EXPECT_EQ(first.value()->key(), key);
    EXPECT_EQ(first.value()->size(), 8);
    EXPECT_EQ(evaluator.cachedBytes(), first.value()->bytes());

    evaluator.invalidate(source.contentHash());
    ASSERT_TRUE(evaluator.tile(source, key));
    EXPECT_EQ(source.calls, 2);
}

TEST(TileEvaluator, SharesTilesBetweenSourcesWithEqualContent) {
    TileEvaluator evaluator(TileFormat{8, 1});
    CountingSource a("a", 42), b("b", 42), other("c", 43);
    ASSERT_EQ(a.contentHash(), b.contentHash());
    ASSERT_NE(a.contentHash(), other.contentHash());
    const TileKey key{2, 0, 1, 1};
    Result<TilePointer> fromA = evaluator.tile(a, key);
    Result<TilePointer> fromB = evaluator.tile(b, key);
    ASSERT_TRUE(fromA);
    ASSERT_TRUE(fromB);
    EXPECT_EQ(fromA.value(), fromB.value());
    EXPECT_EQ(a.calls, 1);
    EXPECT_EQ(b.calls, 0);
    ASSERT_TRUE(evaluator.tile(other, key));
    EXPECT_EQ(other.calls, 1);
}

TEST(TileEvaluator, FailedTileIsProducedOnceAndTheErrorRepeats) {
    TileEvaluator evaluator(TileFormat{8, 1});
    CountingSource broken("broken", 7, true);
    const TileKey key{1, 0, 2, 1};
    Result<TilePointer> first = evaluator.tile(broken, key);
    ASSERT_FALSE(first);
    EXPECT_EQ(first.error().message, "source 'broken', tile L1/k0/x2/y1: disk on fire");
    Result<TilePointer> second = evaluator.tile(broken, key);
    ASSERT_FALSE(second);
    EXPECT_EQ(second.error().message, first.error().message);
    EXPECT_EQ(broken.calls, 1);
    EXPECT_EQ(evaluator.statistics().failures, 1u);
    // Another tile of the same source is a distinct failure.
    ASSERT_FALSE(evaluator.tile(broken, TileKey{1, 0, 3, 1}));
    EXPECT_EQ(broken.calls, 2);
    // Invalidation forgets the failure: the next request retries.
    evaluator.invalidate(broken.contentHash());
    ASSERT_FALSE(evaluator.tile(broken, key));
    EXPECT_EQ(broken.calls, 3);
}

}  // namespace
}  // namespace sylva
