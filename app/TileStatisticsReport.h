// TileStatisticsReport: `--tile-stats` of `sylva render` and `sylva watch` — where the
// tile time of a run went, per source, printed to stderr: tiles produced, read from the
// disk cache, cache hits, tiles evicted for the memory budget, produce seconds (own time,
// without nested inputs), and what the cache holds at the end (tiles, MiB) against the
// budget and the peak. Each print reports the change since the previous one (the first:
// since the process started), so a watch shows what an edit recomputed and evicted.
// Counters are kept per content hash (an edited source's new content counts from zero)
// and printed summed by source name (the scenarios' copies of a source, the old and new
// content of an edited one).
#pragma once

#include <cstdint>
#include <cstdio>
#include <map>
#include <string>

#include "sylva/core/scheduler/Scheduler.h"

namespace sylva::app {

class TileStatisticsReport {
public:
    // Prints the table for the run since the previous print to `out`, then remembers the
    // counters. The scheduler must be the same one on every call.
    void print(const Scheduler& scheduler, std::FILE* out);

private:
    std::map<std::uint64_t, SchedulerStatistics> previous_;  // by content hash
};

}  // namespace sylva::app
