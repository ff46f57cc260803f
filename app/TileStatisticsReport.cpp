#include "TileStatisticsReport.h"

#include <memory>
#include <string>
#include <vector>

namespace sylva::app {
namespace {

// The counters of `now` minus those of `before` (the same content hash); the cached
// tiles and bytes stay `now`'s. A hash dropped and made again between two prints (an
// edit undone) counts from zero: all of `now`.
SchedulerStatistics since(const SchedulerStatistics& now, const SchedulerStatistics& before) {
    SchedulerStatistics change = now;
    if (now.hits < before.hits || now.misses < before.misses || now.diskHits < before.diskHits ||
        now.evictions < before.evictions || now.failures < before.failures) {
        return change;
    }
    change.hits -= before.hits;
    change.misses -= before.misses;
    change.diskHits -= before.diskHits;
    change.evictions -= before.evictions;
    change.failures -= before.failures;
    change.produceSeconds -= before.produceSeconds;
    return change;
}

void printRow(std::FILE* out, const std::string& name, const SchedulerStatistics& s) {
    std::fprintf(out, "%-28s %9zu %9zu %9zu %9zu %11.2f %7zu %9.1f\n", name.c_str(), s.misses,
                 s.diskHits, s.hits, s.evictions, s.produceSeconds, s.tiles,
                 static_cast<double>(s.bytes) / (1 << 20));
}

void printDiskCache(const DiskTileCache& disk, std::FILE* out) {
    const DiskTileCacheStatistics d = disk.statistics();
    std::fprintf(out,
                 "disk cache %s: %llu hits, %llu misses, %llu written (%.1f MiB), %llu "
                 "failed writes, %llu corrupt; read %.2f s, write %.2f s\n",
                 disk.folder().string().c_str(), static_cast<unsigned long long>(d.hits),
                 static_cast<unsigned long long>(d.misses),
                 static_cast<unsigned long long>(d.writes),
                 static_cast<double>(d.bytesWritten) / (1 << 20),
                 static_cast<unsigned long long>(d.writeFailures),
                 static_cast<unsigned long long>(d.corrupt), d.readSeconds, d.writeSeconds);
}

}  // namespace

void TileStatisticsReport::print(const Scheduler& scheduler, std::FILE* out) {
    const std::vector<SchedulerStatistics> now = scheduler.statisticsPerSource();
    std::map<std::string, SchedulerStatistics> byName;
    SchedulerStatistics total;
    std::map<std::uint64_t, SchedulerStatistics> next;
    for (const SchedulerStatistics& source : now) {
        const auto before = previous_.find(source.hash);
        const SchedulerStatistics change =
            before == previous_.end() ? source : since(source, before->second);
        byName[source.name] += change;
        total += change;
        next.emplace(source.hash, source);
    }
    std::fprintf(out, "%-28s %9s %9s %9s %9s %11s %7s %9s\n", "source", "produced", "from disk",
                 "hits", "evicted", "produce s", "cached", "MiB");
    for (const auto& [name, statistics] : byName) {
        printRow(out, name, statistics);
    }
    printRow(out, "total", total);
    std::fprintf(out, "tile cache: budget %.0f MiB, peak %.1f MiB\n",
                 static_cast<double>(scheduler.budgetBytes()) / (1 << 20),
                 static_cast<double>(scheduler.peakCachedBytes()) / (1 << 20));
    if (const std::shared_ptr<DiskTileCache>& disk = scheduler.diskCache()) {
        printDiskCache(*disk, out);
    }
    previous_ = std::move(next);
}

}  // namespace sylva::app
