#include "sylva/core/tiles/DiskTileCache.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <mutex>
#include <string>
#include <vector>

#include "sylva/core/scheduler/Scheduler.h"

namespace sylva {
namespace {

std::filesystem::path freshFolder(const std::string& name) {
    const auto folder = std::filesystem::temp_directory_path() /
                        ("sylva_disk_cache_" + std::to_string(::getpid())) / name;
    std::filesystem::remove_all(folder);
    std::filesystem::create_directories(folder);
    return folder;
}

// A tile whose texels depend on the key and a tag in a way no compressor shortcut can
// fake: smooth terrain-like values plus low-bit noise, and the special floats.
ImageTile makeTile(const TileKey& key, int channels, std::uint32_t tag) {
    ImageTile tile(key, 32, 2, channels);
    std::uint32_t state = tag * 2654435761u + static_cast<std::uint32_t>(key.x * 131 + key.y);
    for (std::size_t i = 0; i < tile.texels().size(); ++i) {
        state = state * 1664525u + 1013904223u;
        tile.texels()[i] = 1000.0f * std::sin(0.01f * static_cast<float>(i) + tag) +
                           static_cast<float>(state >> 20) * 1e-4f;
    }
    tile.texels()[0] = std::numeric_limits<float>::quiet_NaN();
    tile.texels()[1] = -0.0f;
    tile.texels()[2] = std::numeric_limits<float>::infinity();
    return tile;
}

bool sameBits(const ImageTile& a, const ImageTile& b) {
    return a.key() == b.key() && a.size() == b.size() && a.border() == b.border() &&
           a.channels() == b.channels() &&
           std::memcmp(a.texels().data(), b.texels().data(), a.bytes()) == 0;
}

struct WarningLog {
    std::mutex mutex;
    std::vector<std::string> messages;
    std::function<void(const std::string&)> sink() {
        return [this](const std::string& message) {
            std::lock_guard lock(mutex);
            messages.push_back(message);
        };
    }
};

const TileFormat kFormat{32, 2};

TEST(DiskTileCache, RoundTripIsBitIdentical) {
    for (int channels : {1, 3, 4}) {
        const ImageTile tile = makeTile(TileKey{5, 1, 12, 7}, channels, 3);
        const std::string bytes = DiskTileCache::encode(0xABCDEF, tile);
        // Byte planes + zstd: well below the raw float size for smooth data.
        EXPECT_LT(bytes.size(), tile.bytes());
        Result<TilePointer> decoded = DiskTileCache::decode(bytes, 0xABCDEF, tile.key());
        ASSERT_TRUE(decoded) << decoded.error().message;
        EXPECT_TRUE(sameBits(*decoded.value(), tile));
    }
}

TEST(DiskTileCache, DecodeRejectsDamagedEntries) {
    const ImageTile tile = makeTile(TileKey{3, 0, 2, 1}, 1, 1);
    const std::string bytes = DiskTileCache::encode(42, tile);
    const auto error = [&](std::string changed, std::uint64_t hash = 42,
                           TileKey key = TileKey{3, 0, 2, 1}) {
        Result<TilePointer> decoded = DiskTileCache::decode(changed, hash, key);
        return decoded ? std::string("accepted") : decoded.error().message;
    };
    EXPECT_NE(error(bytes.substr(0, 40)).find("truncated"), std::string::npos);
    EXPECT_NE(error(bytes.substr(0, bytes.size() - 10)).find("truncated"), std::string::npos);
    std::string payload = bytes;
    payload[DiskTileCache::kHeaderBytes + payload.size() / 3] ^= 0x10;
    EXPECT_NE(error(payload), "accepted");
    std::string version = bytes;
    version[8] = 7;  // format version field
    EXPECT_NE(error(version).find("format version 7"), std::string::npos);
    std::string header = bytes;
    header[30] ^= 1;  // inside the key: the header hash no longer matches
    EXPECT_NE(error(header).find("header checksum"), std::string::npos);
    EXPECT_NE(error(bytes, 43).find("another tile"), std::string::npos);
    EXPECT_NE(error(bytes, 42, TileKey{3, 0, 2, 0}).find("another tile"), std::string::npos);
    EXPECT_NE(error("GIF89a" + bytes).find("bad magic"), std::string::npos);
}

TEST(DiskTileCache, CorruptEntryIsRemovedRecomputedAndWarnedOnce) {
    WarningLog warnings;
    DiskTileCache cache({freshFolder("corrupt"), 1 << 30, warnings.sink(), {}});
    const ImageTile a = makeTile(TileKey{4, 0, 1, 1}, 1, 1);
    const ImageTile b = makeTile(TileKey{4, 0, 2, 1}, 1, 1);
    cache.store(7, kFormat, a);
    cache.store(7, kFormat, b);
    for (const ImageTile* tile : {&a, &b}) {
        const auto path = cache.entryPath(7, tile->key(), kFormat);
        std::fstream file(path, std::ios::in | std::ios::out | std::ios::binary);
        file.seekp(200);
        file.put('\x5A');
    }
    EXPECT_EQ(cache.load(7, a.key(), kFormat), nullptr);
    EXPECT_EQ(cache.load(7, b.key(), kFormat), nullptr);
    EXPECT_FALSE(std::filesystem::exists(cache.entryPath(7, a.key(), kFormat)));
    EXPECT_EQ(cache.statistics().corrupt, 2u);
    ASSERT_EQ(warnings.messages.size(), 1u);
    EXPECT_NE(warnings.messages[0].find("removed and recomputed"), std::string::npos);
    cache.store(7, kFormat, a);  // what the scheduler does after recomputing
    TilePointer again = cache.load(7, a.key(), kFormat);
    ASSERT_NE(again, nullptr);
    EXPECT_TRUE(sameBits(*again, a));
}

TEST(DiskTileCache, InjectedDiskFullLeavesNothingHalfWritten) {
    WarningLog warnings;
    const auto folder = freshFolder("enospc");
    std::atomic<int> failing{2};
    DiskTileCacheOptions options{folder, 1 << 30, warnings.sink(), {}};
    options.injectWriteError = [&](const std::filesystem::path&) {
        return failing-- > 0 ? ENOSPC : 0;
    };
    DiskTileCache cache(options);
    const ImageTile tile = makeTile(TileKey{2, 0, 1, 1}, 4, 9);
    cache.store(1, kFormat, tile);
    cache.store(1, kFormat, tile);
    EXPECT_EQ(cache.load(1, tile.key(), kFormat), nullptr);
    EXPECT_EQ(cache.statistics().writeFailures, 2u);
    ASSERT_EQ(warnings.messages.size(), 1u);
    EXPECT_NE(warnings.messages[0].find(std::strerror(ENOSPC)), std::string::npos);
    Result<DiskTileCacheUsage> usage = DiskTileCache::scan(folder);
    ASSERT_TRUE(usage);
    EXPECT_EQ(usage->entries + usage->temporaryFiles, 0u);
    cache.store(1, kFormat, tile);  // space again: a full disk does not disable the cache
    TilePointer stored = cache.load(1, tile.key(), kFormat);
    ASSERT_NE(stored, nullptr);
    EXPECT_TRUE(sameBits(*stored, tile));
}

TEST(DiskTileCache, UnwritableFolderWarnsOnceAndStopsWriting) {
    WarningLog warnings;
    // A folder below a regular file cannot be created, even by root.
    const auto blocker = freshFolder("unwritable") / "file";
    std::ofstream(blocker) << "x";
    DiskTileCache cache({blocker / "tiles", 1 << 30, warnings.sink(), {}});
    for (int i = 0; i < 5; ++i) {
        cache.store(1, kFormat, makeTile(TileKey{3, 0, i, 0}, 1, 1));
        EXPECT_EQ(cache.load(1, TileKey{3, 0, i, 0}, kFormat), nullptr);
    }
    EXPECT_EQ(cache.statistics().writeFailures, 1u);  // then writing stopped
    ASSERT_EQ(warnings.messages.size(), 1u);
    EXPECT_NE(warnings.messages[0].find("rendering goes on"), std::string::npos);
}

TEST(DiskTileCache, PruneRemovesLeastRecentlyUsedFirst) {
    const auto folder = freshFolder("prune");
    DiskTileCache cache({folder, 1 << 30, {}, {}});
    std::vector<TileKey> keys;
    for (int i = 0; i < 6; ++i) {
        keys.push_back(TileKey{4, 0, i, 3});
        cache.store(5, kFormat, makeTile(keys.back(), 1, static_cast<std::uint32_t>(i)));
        // Ages one minute apart: key 0 oldest.
        const timespec times[2] = {{1700000000 + 60 * i, 0}, {1700000000 + 60 * i, 0}};
        ASSERT_EQ(::utimensat(AT_FDCWD, cache.entryPath(5, keys.back(), kFormat).c_str(), times, 0),
                  0);
    }
    ASSERT_NE(cache.load(5, keys[0], kFormat), nullptr);  // touched: now the newest
    std::uint64_t entryBytes = std::filesystem::file_size(cache.entryPath(5, keys[5], kFormat));
    // Room for about three entries.
    Result<DiskTileCachePruneReport> report =
        DiskTileCache::prune(folder, entryBytes * 3 + entryBytes / 2);
    ASSERT_TRUE(report) << report.error().message;
    EXPECT_EQ(report->keptEntries, 3u);
    for (int i : {0, 4, 5}) {
        EXPECT_TRUE(std::filesystem::exists(cache.entryPath(5, keys[i], kFormat))) << i;
    }
    for (int i : {1, 2, 3}) {
        EXPECT_FALSE(std::filesystem::exists(cache.entryPath(5, keys[i], kFormat))) << i;
    }
    Result<DiskTileCachePruneReport> cleared = DiskTileCache::clear(folder);
    ASSERT_TRUE(cleared);
    EXPECT_EQ(cleared->removedEntries, 3u);
    EXPECT_EQ(DiskTileCache::scan(folder)->entries, 0u);
}

TEST(DiskTileCache, OtherFormatVersionsAreIgnoredAndPrunedFirst) {
    const auto folder = freshFolder("versions");
    std::filesystem::create_directories(folder / "v0" / "s32b2" / "0000000000000001");
    std::ofstream(folder / "v0" / "s32b2" / "0000000000000001" / "L1-k0-x0-y0.tile") << "old";
    DiskTileCache cache({folder, 1 << 30, {}, {}});
    cache.store(1, kFormat, makeTile(TileKey{1, 0, 0, 0}, 1, 1));
    Result<DiskTileCacheUsage> usage = DiskTileCache::scan(folder);
    ASSERT_TRUE(usage);
    EXPECT_EQ(usage->entries, 1u);
    EXPECT_EQ(usage->otherVersionEntries, 1u);
    Result<DiskTileCachePruneReport> report = DiskTileCache::prune(folder, 1 << 30);
    ASSERT_TRUE(report);
    EXPECT_EQ(report->removedEntries, 1u);
    EXPECT_EQ(DiskTileCache::scan(folder)->otherVersionEntries, 0u);
}

// Two processes write and read the same keys at once, many times: every entry left is
// valid and equal to the tile, every successful read was valid, no temporary file stays.
TEST(DiskTileCache, TwoProcessesWritingTheSameTilesLeaveOnlyValidEntries) {
    const auto folder = freshFolder("stress");
    constexpr int kTiles = 24;
    constexpr int kRounds = 15;
    std::vector<pid_t> children;
    for (int process = 0; process < 2; ++process) {
        const pid_t child = ::fork();
        ASSERT_GE(child, 0);
        if (child == 0) {
            DiskTileCache cache({folder, 1 << 30, {}, {}});
            int bad = 0;
            for (int round = 0; round < kRounds; ++round) {
                for (int i = 0; i < kTiles; ++i) {
                    const int x = process == 0 ? i : kTiles - 1 - i;  // meet in the middle
                    const ImageTile tile = makeTile(TileKey{5, 0, x, 2}, 3, 4);
                    cache.store(99, kFormat, tile);
                    TilePointer read = cache.load(99, tile.key(), kFormat);
                    bad += read != nullptr && !sameBits(*read, tile) ? 1 : 0;
                }
            }
            bad += static_cast<int>(cache.statistics().corrupt);
            ::_exit(bad == 0 ? 0 : 1);
        }
        children.push_back(child);
    }
    for (pid_t child : children) {
        int status = 0;
        ASSERT_EQ(::waitpid(child, &status, 0), child);
        EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << "a reader saw a bad tile";
    }
    DiskTileCache cache({folder, 1 << 30, {}, {}});
    for (int x = 0; x < kTiles; ++x) {
        const ImageTile tile = makeTile(TileKey{5, 0, x, 2}, 3, 4);
        TilePointer read = cache.load(99, tile.key(), kFormat);
        ASSERT_NE(read, nullptr) << x;
        EXPECT_TRUE(sameBits(*read, tile)) << x;
    }
    Result<DiskTileCacheUsage> usage = DiskTileCache::scan(folder);
    ASSERT_TRUE(usage);
    EXPECT_EQ(usage->entries, static_cast<std::uint64_t>(kTiles));
    EXPECT_EQ(usage->temporaryFiles, 0u);
}

// A source whose tiles are expensive to fake: counts produce() calls.
class CountingSource final : public Source {
public:
    explicit CountingSource(std::uint64_t tag)
        : Source("counting", "test", PortType::Elevation, 1), tag_(tag) {
        setParameterHash(tag);
    }
    Result<TilePointer> produce(const TileKey& key, TileProvider& provider) const override {
        ++calls;
        auto tile =
            std::make_shared<ImageTile>(key, provider.format().size, provider.format().border, 1);
        for (std::size_t i = 0; i < tile->texels().size(); ++i) {
            tile->texels()[i] =
                static_cast<float>(std::sqrt(double(i) + double(tag_) + key.x * 7.0 + key.y));
        }
        return TilePointer(std::move(tile));
    }
    mutable std::atomic<int> calls{0};

private:
    std::uint64_t tag_;
};

TEST(DiskTileCache, SchedulerReadsWarmTilesInsteadOfProducing) {
    const auto folder = freshFolder("scheduler");
    std::vector<TileKey> keys;
    for (int x = 0; x < 8; ++x) {
        keys.push_back(TileKey{4, 0, x, 5});
    }
    std::vector<TilePointer> cold;
    {
        CountingSource source(3);
        SchedulerOptions options;
        options.format = kFormat;
        options.workers = 2;
        options.diskCache = std::make_shared<DiskTileCache>(
            DiskTileCacheOptions{folder, std::uint64_t{1} << 30, {}, {}});
        Scheduler scheduler(options);
        for (const TileKey& key : keys) {
            cold.push_back(scheduler.tile(source, key).value());
        }
        EXPECT_EQ(source.calls.load(), 8);
        EXPECT_EQ(options.diskCache->statistics().writes, 8u);
    }
    // Another "process": a new scheduler and a new source object of the same content.
    CountingSource source(3);
    SchedulerOptions options;
    options.format = kFormat;
    options.workers = 2;
    WarningLog warnings;
    options.diskCache = std::make_shared<DiskTileCache>(
        DiskTileCacheOptions{folder, std::uint64_t{1} << 30, warnings.sink(), {}});
    // One entry damaged on disk: recomputed, with one warning.
    {
        std::ofstream damage(options.diskCache->entryPath(source.contentHash(), keys[3], kFormat),
                             std::ios::binary | std::ios::trunc);
        damage << "SYLVATIL";
    }
    Scheduler scheduler(options);
    for (std::size_t i = 0; i < keys.size(); ++i) {
        TilePointer warm = scheduler.tile(source, keys[i]).value();
        EXPECT_TRUE(sameBits(*warm, *cold[i])) << i;
    }
    EXPECT_EQ(source.calls.load(), 1);  // only the damaged one
    EXPECT_EQ(scheduler.totals().diskHits, 7u);
    EXPECT_EQ(scheduler.totals().misses, 1u);
    EXPECT_EQ(warnings.messages.size(), 1u);
    // A source with other content never sees these entries.
    CountingSource other(4);
    (void)scheduler.tile(other, keys[0]);
    EXPECT_EQ(other.calls.load(), 1);
}

}  // namespace
}  // namespace sylva
