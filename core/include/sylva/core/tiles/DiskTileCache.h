// DiskTileCache: the persistent tile cache that seed 001's future work names (§8: "a
// persistent tile cache"), shared by processes and machines on one filesystem.
//
// An entry is one produced ImageTile, keyed by (source content hash, tile key, tile
// format, entry format version). Content hashes cover a source's kind, parameters and
// inputs, and for sources that read files the file's path, size and modification time
// (raster, features) or its bytes (plant_model), so an edited input gives new keys and a
// stale tile is never served. Layout under the folder:
//   v<kFormatVersion>/s<size>b<border>/<source hash, 16 hex>/L<level>-k<k>-x<x>-y<y>.tile
// Entry bytes: a 72-byte little-endian header (magic "SYLVATIL", version, the key,
// size/border/channels, payload length, a hash of the header) and a zstd frame (level 1,
// with zstd's XXH64 content checksum) of the texels byte-shuffled (all first bytes of
// the floats, then all second bytes...), which compresses smooth float data far better.
//
// Concurrency: entries are written to a temporary file named after host, process and a
// counter in the entry's folder and renamed into place, so readers on any machine see
// either no entry or a complete one; two writers of one key both write valid, equal
// entries and the last rename wins. Reading never locks.
//
// Failures never fail a render: a missing, truncated, corrupt or foreign-version entry is
// a miss (corrupt ones are removed and counted; the first is reported through the
// warning sink), and a failed write (unwritable folder, ENOSPC) removes its temporary
// file, is counted, and the first one is reported; after a write failure in an
// unwritable folder the cache stops writing for the rest of the process (reads go on).
//
// Budget: least recently used entries go first. A read hit touches the entry's
// modification time, which is the LRU clock (access times are unreliable under
// relatime/noatime). The process prunes the folder after writing budget/16 bytes since
// its last prune (one thread at a time); `sylva cache prune` does it on demand.
#pragma once

#include <atomic>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <mutex>
#include <string>
#include <string_view>
#include <vector>

#include "sylva/core/base/Result.h"
#include "sylva/core/tiles/ImageTile.h"
#include "sylva/core/tiles/TileProvider.h"

namespace sylva {

struct DiskTileCacheOptions {
    std::filesystem::path folder;
    std::uint64_t budgetBytes = std::uint64_t{16384} << 20;  // all versions together
    // Receives the first warning of each kind (corrupt entry, failed write); may be called
    // from any thread, never under the cache's locks.
    std::function<void(const std::string&)> warningSink;
    // Test hook: called before each entry write with the entry's path; a non-empty
    // errno value makes the write fail as if the system call had (e.g. ENOSPC).
    std::function<int(const std::filesystem::path&)> injectWriteError;
};

struct DiskTileCacheStatistics {
    std::uint64_t hits = 0;           // tiles read from disk
    std::uint64_t misses = 0;         // lookups with no (valid) entry
    std::uint64_t corrupt = 0;        // entries rejected (checksum, truncation, version)
    std::uint64_t writes = 0;         // entries written
    std::uint64_t writeFailures = 0;  // writes that failed (folder, disk full)
    std::uint64_t bytesWritten = 0;   // compressed bytes written
    std::uint64_t prunedEntries = 0;  // entries this process removed for the budget
    double readSeconds = 0;           // reading + decompressing hits and misses
    double writeSeconds = 0;          // compressing + writing
};

// What is in a cache folder (from a scan; other processes may change it meanwhile).
struct DiskTileCacheUsage {
    std::uint64_t entries = 0;  // entries of the current format version
    std::uint64_t bytes = 0;    // their bytes
    std::uint64_t sources = 0;  // distinct source hashes among them
    std::uint64_t otherVersionEntries = 0;
    std::uint64_t otherVersionBytes = 0;
    std::uint64_t temporaryFiles = 0;  // unfinished writes (or ones a crash left)
    std::uint64_t temporaryBytes = 0;
};

struct DiskTileCachePruneReport {
    std::uint64_t removedEntries = 0;
    std::uint64_t removedBytes = 0;
    std::uint64_t keptEntries = 0;
    std::uint64_t keptBytes = 0;
};

class DiskTileCache {
public:
    static constexpr std::uint32_t kFormatVersion = 1;
    static constexpr std::size_t kHeaderBytes = 72;

    explicit DiskTileCache(DiskTileCacheOptions options);
    DiskTileCache(const DiskTileCache&) = delete;
    DiskTileCache& operator=(const DiskTileCache&) = delete;

    const std::filesystem::path& folder() const { return options_.folder; }
    std::uint64_t budgetBytes() const { return options_.budgetBytes; }

    // The entry's tile, or nullptr (miss, or a rejected entry, which is removed).
    // Thread-safe.
    TilePointer load(std::uint64_t sourceHash, const TileKey& key, const TileFormat& format);
    // Writes the entry atomically (see above); failures are counted and warned about,
    // never returned. Thread-safe.
    void store(std::uint64_t sourceHash, const TileFormat& format, const ImageTile& tile);

    DiskTileCacheStatistics statistics() const;
    std::filesystem::path entryPath(std::uint64_t sourceHash, const TileKey& key,
                                    const TileFormat& format) const;

    // The default folder: $SYLVA_CACHE_DIR/tiles, else $XDG_CACHE_HOME/sylva/tiles, else
    // ~/.cache/sylva/tiles (the plant model cache's base folder, plus "tiles").
    static std::filesystem::path defaultFolder();

    // Entry bytes of a tile, and the tile of entry bytes (an Error names what is wrong:
    // truncated, bad magic, other version, key mismatch, checksum). Exposed for tests.
    static std::string encode(std::uint64_t sourceHash, const ImageTile& tile);
    static Result<TilePointer> decode(std::string_view bytes, std::uint64_t sourceHash,
                                      const TileKey& key);

    // Folder maintenance for `sylva cache`; errors name the folder and the reason.
    static Result<DiskTileCacheUsage> scan(const std::filesystem::path& folder);
    // Removes least recently used entries until the folder holds at most `budgetBytes`,
    // entries of other format versions first, and temporary files older than an hour.
    static Result<DiskTileCachePruneReport> prune(const std::filesystem::path& folder,
                                                  std::uint64_t budgetBytes);
    // Removes every entry and temporary file below the folder (the folder stays).
    static Result<DiskTileCachePruneReport> clear(const std::filesystem::path& folder);

private:
    void warnOnce(std::atomic<bool>& warned, const std::string& message);
    void pruneIfDue(std::uint64_t written);
    // Writes bytes to `path` through a temporary file; returns 0 or the errno value.
    int writeAtomically(const std::filesystem::path& path, std::string_view bytes);

    DiskTileCacheOptions options_;
    std::atomic<std::uint64_t> hits_{0}, misses_{0}, corrupt_{0}, writes_{0}, writeFailures_{0},
        bytesWritten_{0}, prunedEntries_{0};
    std::atomic<std::uint64_t> readNanoseconds_{0}, writeNanoseconds_{0};
    std::atomic<std::uint64_t> writtenSincePrune_{0};
    std::atomic<std::uint64_t> temporaryCounter_{0};
    std::atomic<bool> writesDisabled_{false};
    std::atomic<bool> warnedCorrupt_{false}, warnedWrite_{false};
    std::mutex pruneMutex_;
    std::string host_;
};

}  // namespace sylva
