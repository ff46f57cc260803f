#include "sylva/core/tiles/DiskTileCache.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <zstd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <set>
#include <system_error>

#include "sylva/core/base/Hash.h"

namespace sylva {
namespace {

using Clock = std::chrono::steady_clock;
constexpr std::array<char, 8> kMagic = {'S', 'Y', 'L', 'V', 'A', 'T', 'I', 'L'};
constexpr std::string_view kTemporaryPrefix = ".tmp-";
constexpr std::string_view kEntryExtension = ".tile";

std::string hex16(std::uint64_t value) {
    char text[17];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(value));
    return text;
}

// Little-endian field writer/reader over the fixed header.
class HeaderWriter {
public:
    explicit HeaderWriter(std::string& out) : out_(out) {}
    template <typename T>
    void put(T value) {
        for (std::size_t i = 0; i < sizeof(T); ++i) {
            out_.push_back(static_cast<char>(
                (static_cast<std::uint64_t>(static_cast<std::make_unsigned_t<T>>(value)) >>
                 (8 * i)) &
                0xFF));
        }
    }

private:
    std::string& out_;
};

class HeaderReader {
public:
    explicit HeaderReader(std::string_view in) : in_(in) {}
    template <typename T>
    T get() {
        std::uint64_t value = 0;
        for (std::size_t i = 0; i < sizeof(T); ++i) {
            value |= static_cast<std::uint64_t>(static_cast<unsigned char>(in_[offset_ + i]))
                     << (8 * i);
        }
        offset_ += sizeof(T);
        return static_cast<T>(static_cast<std::make_unsigned_t<T>>(value));
    }
    void skip(std::size_t bytes) { offset_ += bytes; }

private:
    std::string_view in_;
    std::size_t offset_ = 0;
};

std::uint64_t headerHash(std::string_view header) {
    return ContentHash().add(header.data(), header.size()).value();
}

// Byte planes of the float texels: plane b holds byte b of every float, so the exponent
// and high mantissa bytes of smooth data form long runs that zstd compresses well.
std::string shuffle(const std::vector<float>& texels) {
    const std::size_t count = texels.size();
    std::string planes(count * sizeof(float), '\0');
    const auto* bytes = reinterpret_cast<const unsigned char*>(texels.data());
    for (std::size_t i = 0; i < count; ++i) {
        for (std::size_t b = 0; b < sizeof(float); ++b) {
            planes[b * count + i] = static_cast<char>(bytes[i * sizeof(float) + b]);
        }
    }
    return planes;
}

void unshuffle(std::string_view planes, std::vector<float>& texels) {
    const std::size_t count = texels.size();
    auto* bytes = reinterpret_cast<unsigned char*>(texels.data());
    for (std::size_t i = 0; i < count; ++i) {
        for (std::size_t b = 0; b < sizeof(float); ++b) {
            bytes[i * sizeof(float) + b] = static_cast<unsigned char>(planes[b * count + i]);
        }
    }
}

// The whole file, or an errno value (ENOENT for a miss).
int readWholeFile(const std::filesystem::path& path, std::string& bytes) {
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) {
        return errno;
    }
    struct stat info {};
    if (::fstat(fd, &info) != 0) {
        const int error = errno;
        ::close(fd);
        return error;
    }
    bytes.resize(static_cast<std::size_t>(info.st_size));
    std::size_t done = 0;
    while (done < bytes.size()) {
        const ssize_t got = ::read(fd, bytes.data() + done, bytes.size() - done);
        if (got < 0 && errno == EINTR) {
            continue;
        }
        if (got <= 0) {
            const int error = got < 0 ? errno : 0;
            ::close(fd);
            bytes.resize(done);  // shorter than its size: decode reports truncation
            return error;
        }
        done += static_cast<std::size_t>(got);
    }
    ::close(fd);
    return 0;
}

std::string hostName() {
    char name[256] = {};
    if (::gethostname(name, sizeof name - 1) != 0 || name[0] == '\0') {
        return "host";
    }
    std::string host(name);
    std::replace(host.begin(), host.end(), '/', '_');
    return host;
}

struct FolderEntry {
    std::filesystem::path path;
    std::uint64_t bytes = 0;
    std::filesystem::file_time_type time;
    bool current = false;    // an entry of kFormatVersion
    bool temporary = false;  // an unfinished write
};

Result<std::vector<FolderEntry>> listFolder(const std::filesystem::path& folder) {
    std::vector<FolderEntry> entries;
    std::error_code error;
    if (!std::filesystem::exists(folder, error)) {
        return entries;  // an empty cache
    }
    std::string currentVersion("v");
    currentVersion += std::to_string(DiskTileCache::kFormatVersion);
    std::filesystem::recursive_directory_iterator it(folder, error), end;
    if (error) {
        return Error{"cannot read tile cache folder " + folder.string() + ": " + error.message()};
    }
    for (; it != end; it.increment(error)) {
        if (error) {
            return Error{"cannot read tile cache folder " + folder.string() + ": " +
                         error.message()};
        }
        std::error_code entryError;
        if (!it->is_regular_file(entryError)) {
            continue;
        }
        const std::string name = it->path().filename().string();
        FolderEntry entry;
        entry.temporary = name.starts_with(kTemporaryPrefix);
        if (!entry.temporary && !name.ends_with(kEntryExtension)) {
            continue;  // not ours
        }
        entry.path = it->path();
        entry.bytes = it->file_size(entryError);
        entry.time = it->last_write_time(entryError);
        const auto relative = std::filesystem::relative(entry.path, folder, entryError);
        entry.current = !relative.empty() && relative.begin()->string() == currentVersion;
        entries.push_back(std::move(entry));
    }
    return entries;
}

}  // namespace

DiskTileCache::DiskTileCache(DiskTileCacheOptions options)
    : options_(std::move(options)), host_(hostName()) {}

std::filesystem::path DiskTileCache::defaultFolder() {
    if (const char* directory = std::getenv("SYLVA_CACHE_DIR"); directory && *directory) {
        return std::filesystem::path(directory) / "tiles";
    }
    if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) {
        return std::filesystem::path(xdg) / "sylva" / "tiles";
    }
    if (const char* home = std::getenv("HOME"); home && *home) {
        return std::filesystem::path(home) / ".cache" / "sylva" / "tiles";
    }
    std::error_code error;
    return std::filesystem::temp_directory_path(error) / "sylva-cache" / "tiles";
}

std::filesystem::path DiskTileCache::entryPath(std::uint64_t sourceHash, const TileKey& key,
                                               const TileFormat& format) const {
    // Appended piecewise: GCC 12's -Wrestrict misfires on `"literal" + std::string`.
    std::string version("v");
    version += std::to_string(kFormatVersion);
    std::string tileFormat("s");
    tileFormat += std::to_string(format.size);
    tileFormat += 'b';
    tileFormat += std::to_string(format.border);
    std::string name("L");
    for (const auto& [prefix, value] : {std::pair<const char*, std::int32_t>{"", key.level},
                                        {"-k", key.lonReduction},
                                        {"-x", key.x},
                                        {"-y", key.y}}) {
        name += prefix;
        name += std::to_string(value);
    }
    name += kEntryExtension;
    return options_.folder / version / tileFormat / hex16(sourceHash) / name;
}

std::string DiskTileCache::encode(std::uint64_t sourceHash, const ImageTile& tile) {
    const std::string planes = shuffle(tile.texels());
    std::string payload(ZSTD_compressBound(planes.size()), '\0');
    ZSTD_CCtx* context = ZSTD_createCCtx();
    SYLVA_CHECK(context != nullptr);
    (void)ZSTD_CCtx_setParameter(context, ZSTD_c_compressionLevel, 1);
    (void)ZSTD_CCtx_setParameter(context, ZSTD_c_checksumFlag, 1);
    const std::size_t compressed =
        ZSTD_compress2(context, payload.data(), payload.size(), planes.data(), planes.size());
    ZSTD_freeCCtx(context);
    SYLVA_CHECK_MESSAGE(!ZSTD_isError(compressed), "zstd compression failed");
    payload.resize(compressed);

    std::string bytes(kMagic.begin(), kMagic.end());
    HeaderWriter header(bytes);
    header.put<std::uint32_t>(kFormatVersion);
    header.put<std::uint32_t>(static_cast<std::uint32_t>(kHeaderBytes));
    header.put<std::uint64_t>(sourceHash);
    header.put<std::int32_t>(tile.key().level);
    header.put<std::int32_t>(tile.key().lonReduction);
    header.put<std::int32_t>(tile.key().x);
    header.put<std::int32_t>(tile.key().y);
    header.put<std::int32_t>(tile.size());
    header.put<std::int32_t>(tile.border());
    header.put<std::int32_t>(tile.channels());
    header.put<std::uint32_t>(0);  // reserved
    header.put<std::uint64_t>(payload.size());
    header.put<std::uint64_t>(headerHash(bytes));
    SYLVA_CHECK(bytes.size() == kHeaderBytes);
    return bytes + payload;
}

Result<TilePointer> DiskTileCache::decode(std::string_view bytes, std::uint64_t sourceHash,
                                          const TileKey& key) {
    if (bytes.size() < kHeaderBytes) {
        return Error{"truncated (" + std::to_string(bytes.size()) + " bytes, header is " +
                     std::to_string(kHeaderBytes) + ")"};
    }
    if (!std::equal(kMagic.begin(), kMagic.end(), bytes.begin())) {
        return Error{"not a tile cache entry (bad magic)"};
    }
    HeaderReader header(bytes);
    header.skip(kMagic.size());
    const auto version = header.get<std::uint32_t>();
    const auto headerBytes = header.get<std::uint32_t>();
    if (version != kFormatVersion || headerBytes != kHeaderBytes) {
        return Error{"entry of format version " + std::to_string(version) + ", expected " +
                     std::to_string(kFormatVersion)};
    }
    const auto hash = header.get<std::uint64_t>();
    TileKey stored;
    stored.level = header.get<std::int32_t>();
    stored.lonReduction = header.get<std::int32_t>();
    stored.x = header.get<std::int32_t>();
    stored.y = header.get<std::int32_t>();
    const auto size = header.get<std::int32_t>();
    const auto border = header.get<std::int32_t>();
    const auto channels = header.get<std::int32_t>();
    (void)header.get<std::uint32_t>();
    const auto payloadBytes = header.get<std::uint64_t>();
    const auto checksum = header.get<std::uint64_t>();
    if (checksum != headerHash(bytes.substr(0, kHeaderBytes - 8))) {
        return Error{"header checksum mismatch"};
    }
    if (hash != sourceHash || stored != key) {
        return Error{"entry holds another tile (" + stored.toString() + ")"};
    }
    if (size <= 0 || size > 65536 || border < 0 || border > 1024 || channels <= 0 || channels > 4) {
        return Error{"implausible tile dimensions"};
    }
    if (payloadBytes != bytes.size() - kHeaderBytes) {
        return Error{"truncated (payload " + std::to_string(bytes.size() - kHeaderBytes) + " of " +
                     std::to_string(payloadBytes) + " bytes)"};
    }
    auto tile = std::make_shared<ImageTile>(stored, size, border, channels);
    std::string planes(tile->texels().size() * sizeof(float), '\0');
    const std::string_view payload = bytes.substr(kHeaderBytes);
    const unsigned long long frameSize = ZSTD_getFrameContentSize(payload.data(), payload.size());
    if (frameSize != planes.size()) {
        return Error{"payload size does not match the tile dimensions"};
    }
    const std::size_t got =
        ZSTD_decompress(planes.data(), planes.size(), payload.data(), payload.size());
    if (ZSTD_isError(got) || got != planes.size()) {
        return Error{std::string("payload corrupt (") +
                     (ZSTD_isError(got) ? ZSTD_getErrorName(got) : "short") + ")"};
    }
    unshuffle(planes, tile->texels());
    return TilePointer(std::move(tile));
}

TilePointer DiskTileCache::load(std::uint64_t sourceHash, const TileKey& key,
                                const TileFormat& format) {
    const auto start = Clock::now();
    const std::filesystem::path path = entryPath(sourceHash, key, format);
    std::string bytes;
    const int error = readWholeFile(path, bytes);
    TilePointer tile;
    if (error == 0) {
        Result<TilePointer> decoded = decode(bytes, sourceHash, key);
        if (decoded) {
            tile = std::move(decoded.value());
            ::utimensat(AT_FDCWD, path.c_str(), nullptr, 0);  // the LRU clock; may fail
        } else {
            ++corrupt_;
            std::error_code ignored;
            std::filesystem::remove(path, ignored);
            warnOnce(warnedCorrupt_, "tile cache: " + path.string() + ": " +
                                         decoded.error().message +
                                         "; removed and recomputed (further corrupt entries "
                                         "are only counted)");
        }
    }
    ++(tile ? hits_ : misses_);
    readNanoseconds_ += static_cast<std::uint64_t>(
        std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - start).count());
    return tile;
}

void DiskTileCache::store(std::uint64_t sourceHash, const TileFormat& format,
                          const ImageTile& tile) {
    if (writesDisabled_) {
        return;
    }
    const auto start = Clock::now();
    const std::filesystem::path path = entryPath(sourceHash, tile.key(), format);
    const std::string bytes = encode(sourceHash, tile);
    const int error = writeAtomically(path, bytes);
    if (error == 0) {
        ++writes_;
        bytesWritten_ += bytes.size();
    } else {
        ++writeFailures_;
        const bool unwritable =
            error == EACCES || error == EPERM || error == EROFS || error == ENOTDIR;
        if (unwritable) {
            writesDisabled_ = true;
        }
        warnOnce(warnedWrite_, "tile cache: cannot write " + path.string() + ": " +
                                   std::strerror(error) +
                                   (unwritable ? "; rendering goes on without writing the cache"
                                               : "; the tile is not cached (further failed "
                                                 "writes are only counted)"));
    }
    writeNanoseconds_ += static_cast<std::uint64_t>(
        std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - start).count());
    if (error == 0) {
        pruneIfDue(bytes.size());
    }
}

int DiskTileCache::writeAtomically(const std::filesystem::path& path, std::string_view bytes) {
    std::error_code folderError;
    std::filesystem::create_directories(path.parent_path(), folderError);
    if (folderError) {
        return folderError.value();
    }
    const std::filesystem::path temporary =
        path.parent_path() /
        (std::string(kTemporaryPrefix) + host_ + "-" + std::to_string(::getpid()) + "-" +
         std::to_string(temporaryCounter_++) + "-" + path.filename().string());
    int error = options_.injectWriteError ? options_.injectWriteError(path) : 0;
    int fd = -1;
    if (error == 0) {
        fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
        error = fd < 0 ? errno : 0;
    }
    for (std::size_t done = 0; error == 0 && done < bytes.size();) {
        const ssize_t wrote = ::write(fd, bytes.data() + done, bytes.size() - done);
        if (wrote < 0 && errno == EINTR) {
            continue;
        }
        if (wrote <= 0) {
            error = wrote < 0 ? errno : EIO;
            break;
        }
        done += static_cast<std::size_t>(wrote);
    }
    if (fd >= 0 && ::close(fd) != 0 && error == 0) {
        error = errno;  // NFS may report ENOSPC/EDQUOT only on close
    }
    if (error == 0 && ::rename(temporary.c_str(), path.c_str()) != 0) {
        error = errno;
    }
    if (error != 0 && fd >= 0) {
        ::unlink(temporary.c_str());
    }
    return error;
}

void DiskTileCache::warnOnce(std::atomic<bool>& warned, const std::string& message) {
    if (!warned.exchange(true) && options_.warningSink) {
        options_.warningSink(message);
    }
}

void DiskTileCache::pruneIfDue(std::uint64_t written) {
    const std::uint64_t interval = std::max<std::uint64_t>(options_.budgetBytes / 16, 1);
    if (writtenSincePrune_.fetch_add(written) + written < interval) {
        return;
    }
    std::unique_lock lock(pruneMutex_, std::try_to_lock);
    if (!lock.owns_lock()) {
        return;  // another thread prunes now
    }
    writtenSincePrune_ = 0;
    // Hysteresis: down to 90 % of the budget, so the next prune is not due at once.
    Result<DiskTileCachePruneReport> report = prune(options_.folder, options_.budgetBytes / 10 * 9);
    if (report) {
        prunedEntries_ += report->removedEntries;
    }
}

DiskTileCacheStatistics DiskTileCache::statistics() const {
    DiskTileCacheStatistics s;
    s.hits = hits_;
    s.misses = misses_;
    s.corrupt = corrupt_;
    s.writes = writes_;
    s.writeFailures = writeFailures_;
    s.bytesWritten = bytesWritten_;
    s.prunedEntries = prunedEntries_;
    s.readSeconds = static_cast<double>(readNanoseconds_.load()) * 1e-9;
    s.writeSeconds = static_cast<double>(writeNanoseconds_.load()) * 1e-9;
    return s;
}

Result<DiskTileCacheUsage> DiskTileCache::scan(const std::filesystem::path& folder) {
    Result<std::vector<FolderEntry>> entries = listFolder(folder);
    if (!entries) {
        return entries.error();
    }
    DiskTileCacheUsage usage;
    std::set<std::filesystem::path> sources;
    for (const FolderEntry& entry : entries.value()) {
        if (entry.temporary) {
            ++usage.temporaryFiles;
            usage.temporaryBytes += entry.bytes;
        } else if (entry.current) {
            ++usage.entries;
            usage.bytes += entry.bytes;
            sources.insert(entry.path.parent_path());
        } else {
            ++usage.otherVersionEntries;
            usage.otherVersionBytes += entry.bytes;
        }
    }
    usage.sources = sources.size();
    return usage;
}

Result<DiskTileCachePruneReport> DiskTileCache::prune(const std::filesystem::path& folder,
                                                      std::uint64_t budgetBytes) {
    Result<std::vector<FolderEntry>> listed = listFolder(folder);
    if (!listed) {
        return listed.error();
    }
    std::vector<FolderEntry>& entries = listed.value();
    const auto staleTemporary =
        std::filesystem::file_time_type::clock::now() - std::chrono::hours(1);
    // Removal order: stale temporary files, other versions, then oldest first.
    std::sort(entries.begin(), entries.end(), [](const FolderEntry& a, const FolderEntry& b) {
        if (a.current != b.current) {
            return !a.current;
        }
        return a.time < b.time;
    });
    DiskTileCachePruneReport report;
    std::uint64_t total = 0;
    for (const FolderEntry& entry : entries) {
        total += entry.temporary ? 0 : entry.bytes;
    }
    for (const FolderEntry& entry : entries) {
        std::error_code error;
        if (entry.temporary) {
            if (entry.time < staleTemporary && std::filesystem::remove(entry.path, error)) {
                ++report.removedEntries;
                report.removedBytes += entry.bytes;
            }
            continue;
        }
        if ((total > budgetBytes || !entry.current) && std::filesystem::remove(entry.path, error)) {
            total -= entry.bytes;
            ++report.removedEntries;
            report.removedBytes += entry.bytes;
            continue;
        }
        ++report.keptEntries;
        report.keptBytes += entry.bytes;
    }
    return report;
}

Result<DiskTileCachePruneReport> DiskTileCache::clear(const std::filesystem::path& folder) {
    Result<std::vector<FolderEntry>> listed = listFolder(folder);
    if (!listed) {
        return listed.error();
    }
    DiskTileCachePruneReport report;
    for (const FolderEntry& entry : listed.value()) {
        std::error_code error;
        if (std::filesystem::remove(entry.path, error)) {
            ++report.removedEntries;
            report.removedBytes += entry.bytes;
        } else if (error) {
            return Error{"cannot remove " + entry.path.string() + ": " + error.message()};
        }
    }
    // Empty folders below (the cache folder itself stays).
    std::error_code error;
    for (const auto& child : std::filesystem::directory_iterator(folder, error)) {
        if (child.is_directory(error) && child.path().filename().string().starts_with("v")) {
            std::filesystem::remove_all(child.path(), error);
        }
    }
    return report;
}

}  // namespace sylva
