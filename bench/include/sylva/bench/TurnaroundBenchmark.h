// TurnaroundBenchmark: `sylva bench turnaround`, how fast a planner sees results on a
// real project (issue "scenarios, comparisons, series, paths, watch"), by running a real
// `sylva` binary on a temporary copy of the project (written next to it, so relative
// data paths hold, and removed afterwards, as is the output folder in the temporary
// folder):
//   cold_render_s       a fresh `sylva render` process for one view (first camera and
//                       scenario of the series): start-up, GL, every tile, the image;
//   warm_edit_s         `sylva watch` on that view: after its first image, a colour
//                       adjustment (`saturation` of an `adjust` source) is edited in the
//                       copy; the time from the write to the watch's new image;
//   edit_ratio          warm_edit_s / cold_render_s (target ≤ 0.3);
//   warm_edit_tiles     the tiles the watch produced for the edit (its "N tiles
//                       recomputed"; load-independent: the changed branch plus whatever
//                       the tile budget had evicted that the new image needs);
//   series_s_per_image  one process rendering the series (default views block
//                       `photo_points`: 3 cameras × 3 scenarios × 2 times = 18 images,
//                       --no-comparisons) divided by its image count;
//   shard_speedup       that series' wall time over the wall time of two `--shard i/2`
//                       processes started together (target ≥ 1.6);
//   warm_disk_start_ratio  a second one-view process whose disk tile cache the first
//                       filled, over cold_render_s (target ≤ 0.3);
//   shard_cpu_overhead  CPU seconds (user + system) of two `--shard i/2` processes
//                       sharing one initially empty disk cache, over the CPU seconds of
//                       the one-process series (target ≤ 1.1);
//   cache_write_overhead  the first of those one-view processes (cold, writing the disk
//                       cache) over cold_render_s (target ≤ 1.1).
// Every process starts with cold memory; all but the disk cache measurements run with
// --no-disk-cache (so the user's default disk cache never warms them), those use empty
// folders of their own. Seconds of wall time. With `diskOnly` (`--disk-only`, the
// reduced mode) warm_edit_s, edit_ratio, warm_edit_tiles and shard_speedup are not
// measured; with `editOnly` (`--edit-only`) only cold_render_s and the three edit keys.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include "sylva/bench/BenchmarkMetrics.h"
#include "sylva/core/base/Result.h"
#include "sylva/core/model/ProjectModel.h"

namespace sylva::bench {

struct TurnaroundBenchmarkOptions {
    // The `sylva` binary to run (`render`, `watch`); the CLI passes itself (/proc/self/exe).
    std::filesystem::path executable;
    std::filesystem::path projectFile = "projects/olinda/olinda.sylva";
    std::string views = "photo_points";  // the series measured
    int width = 1280, height = 720;      // --size of every process
    std::string gl = "egl";              // --gl of every process, passed as given
    bool diskOnly = false;               // the reduced mode (see above)
    bool editOnly = false;               // cold render and warm edit only (see above)
};

struct TurnaroundBenchmarkResult {
    MetricList metrics;        // in the order above
    std::size_t images = 0;    // the series' image count
    std::string json() const;  // {"suite":"turnaround","metrics":{...}}, %.4g
};

// `model` and `scenarios` are the loaded project (the default model and one per
// scenario, as dsl::loadProject gives them); they name the series' cameras and the data
// files, all of which must exist. Fails with a message naming the project and what is
// missing (a views block, its cameras, a data file: "run scripts/fetch-samples", the
// `saturation = N` to edit), or the process that failed and its output.
Result<TurnaroundBenchmarkResult> runTurnaroundBenchmark(
    const TurnaroundBenchmarkOptions& options, const ProjectModel& model,
    const std::vector<ProjectModel>& scenarios);

}  // namespace sylva::bench
