// `sylva watch PROJECT [--views NAME] [--camera NAME] [--out DIR] [--size WxH] [--gl ...]
//                      [--interval-ms N] [--exit-after N] [--tile-stats] [-D name=value]`
// Headless edit loop: renders the chosen views, then watches the project file, its
// imports and every data file its sources read. On a change it parses the project once;
// with errors it prints the diagnostics and keeps the last images; otherwise
// render::BatchRenderer keeps the tiles of every source whose content hash is unchanged
// (Scheduler::retainOnly), recomputes only the rest, rewrites the images and this command
// prints the edit-to-image latency with the number of tiles recomputed (--tile-stats:
// per source, what each render produced, evicted and kept; TileStatisticsReport).
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <optional>
#include <string>
#include <thread>

#include "CommandLine.h"
#include "Commands.h"
#include "ProjectSession.h"
#include "TileStatisticsReport.h"
#include "sylva/core/base/FileWatch.h"
#include "sylva/render/batch/BatchRenderer.h"

namespace sylva::app {
namespace {

std::atomic<bool> stopWatching{false};
void onStop(int) {
    stopWatching.store(true);
}

struct WatchRequest {
    std::filesystem::path project;
    render::BatchOptions options;
    render::BatchSelection selection;  // one viewpoint at a time: images, first path frames
    int intervalMs = 200;
    int exitAfter = 1 << 30;
    bool tileStatistics = false;  // --tile-stats
};

// Prints each image written ("PATH  WxH") and every error.
class WatchPrinter final : public render::BatchListener {
public:
    void jobDone(const render::JobReport& report) override {
        std::printf("%s  %dx%d\n", report.job->output.string().c_str(), report.width,
                    report.height);
    }
    void error(const std::string& message) override { reportError(message); }
};

// `--name N` as a whole number in 1..100000000 (left as it is when absent); false after
// reporting a usage error.
bool positiveInt(const ParsedCommandLine& command, const char* name, int& out) {
    const Result<std::optional<int>> value =
        wholeNumberOption(command, name, 1, 100000000, "expects a positive whole number");
    if (!value) {
        reportError(value.error().message);
        return false;
    }
    out = value.value().value_or(out);
    return true;
}

// Fills `request` from the options; false after reporting a usage error.
bool parseRequest(const ParsedCommandLine& command, WatchRequest& request) {
    if (!command.error.empty() || command.positional.size() != 1) {
        reportError(command.error.empty()
                        ? "watch needs exactly one project file (see 'sylva watch --help')"
                        : command.error);
        return false;
    }
    if (!positiveInt(command, "interval-ms", request.intervalMs) ||
        !positiveInt(command, "exit-after", request.exitAfter)) {
        return false;
    }
    if (std::optional<std::string> size = command.get("size");
        size && !parseSize(*size, request.options.width, request.options.height)) {
        reportError("--size expects WIDTHxHEIGHT within 1..16384, got '" + *size + "'");
        return false;
    }
    // The budget: --cache-mb, else the render block's cache_mb (read on the first render).
    const Result<std::optional<std::size_t>> cache = cacheMegabytesOption(command);
    if (!cache) {
        reportError(cache.error().message);
        return false;
    }
    request.options.cacheMegabytes = cache.value();
    Result<std::optional<render::GlBackend>> backend = glBackendOption(command);
    if (!backend) {
        reportError(backend.error().message);
        return false;
    }
    request.options.backend = backend.value();
    request.project = command.positional[0];
    request.tileStatistics = command.has("tile-stats");
    render::BatchSelection& selection = request.selection;
    selection.outputFolder = command.get("out").value_or("out");
    selection.views = command.get("views").value_or("");
    selection.viewpoint = command.get("camera");
    selection.imagesOnly = true;
    selection.firstFramesOnly = true;
    selection.manifest = false;
    return true;
}

// Parses the project (once) and hands it to `batch`; prints the diagnostics, and the
// error when its graph cannot be built. Returns the project files read (the watch goes
// on with them) and whether `batch` now holds this version of the project.
std::pair<std::vector<std::filesystem::path>, bool> load(const std::filesystem::path& file,
                                                         const ParsedCommandLine& command,
                                                         render::BatchRenderer& batch) {
    dsl::LoadResult loaded = dsl::loadProject(file, loadOptionsFor(command));
    std::vector<std::filesystem::path> files = loaded.files;
    if (files.empty()) {
        files.push_back(file);
    }
    printDiagnostics(loaded);
    if (loaded.hasErrors() || !loaded.model) {
        return {files, false};
    }
    if (Status set = batch.setProject(scenarioModels(std::move(loaded))); !set) {
        reportError(set.error().message);
        return {files, false};
    }
    return {files, true};
}

// Renders the chosen images of the current project; false on errors (already printed).
bool renderAll(render::BatchRenderer& batch, const WatchRequest& request,
               std::chrono::steady_clock::time_point since, TileStatisticsReport& statistics) {
    Result<render::BatchPlan> plan = batch.plan(request.selection);
    if (!plan) {
        reportError(plan.error().message);
        return false;
    }
    if (plan->jobs().empty()) {
        const std::optional<std::string>& camera = request.selection.viewpoint;
        reportError("nothing to render: no image of views '" + request.selection.views + "'" +
                    (camera ? " with camera '" + *camera + "'" : std::string()));
        return false;
    }
    WatchPrinter printer;
    Result<render::BatchSummary> summary = batch.run(plan.value(), printer);
    if (!summary) {
        reportError(summary.error().message);
        return false;
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
    if (request.tileStatistics) {
        statistics.print(batch.scheduler(plan->setup()), stderr);
    }
    std::printf("edit-to-image latency: %.2f s, %zu tiles recomputed, %zu cached\n", seconds,
                summary->tilesProduced, summary->tilesCached);
    std::fflush(stdout);
    return summary->failed == 0;
}

}  // namespace

int runWatch(const std::vector<std::string>& arguments) {
    const ParsedCommandLine command = parseCommandLine(arguments, {{"views"},
                                                                   {"camera"},
                                                                   {"out"},
                                                                   {"size"},
                                                                   {"gl"},
                                                                   {"interval-ms"},
                                                                   {"exit-after"},
                                                                   {"cache-mb"},
                                                                   {"tile-stats", false},
                                                                   {"help", false}});
    if (command.has("help")) {
        std::puts(
            "usage: sylva watch PROJECT [--views NAME] [--camera NAME] [--out DIR] [--size WxH]\n"
            "                   [--gl egl|osmesa|glfw] [--interval-ms N] [--exit-after N] "
            "[--cache-mb N]\n"
            "                   [--tile-stats] [-D name=value]");
        return 0;
    }
    WatchRequest request;
    if (!parseRequest(command, request)) {
        return 2;
    }
    render::BatchRenderer batch(request.options);
    if (Status context = batch.createContext(); !context) {
        reportError(context.error().message);
        return 1;
    }
    std::signal(SIGINT, onStop);
    std::signal(SIGTERM, onStop);
    FileWatch watch;
    // Watches the project files and, when the project loaded, every file its sources read.
    auto startWatching = [&](const std::vector<std::filesystem::path>& projectFiles, bool ok) {
        watch.clear();
        for (const std::filesystem::path& file : projectFiles) {
            watch.watch(file);
        }
        if (ok) {
            for (const std::filesystem::path& file : batch.project().files()) {
                watch.watch(file);
            }
        }
    };
    TileStatisticsReport statistics;
    int renders = 0;
    int status = 0;
    auto since = std::chrono::steady_clock::now();
    auto [files, ok] = load(request.project, command, batch);
    if (ok) {
        status = renderAll(batch, request, since, statistics) ? 0 : 1;
        ++renders;
    }
    startWatching(files, ok);
    std::printf("watching %zu files (Ctrl-C to stop)\n", watch.size());
    std::fflush(stdout);
    while (!stopWatching.load() && renders < request.exitAfter) {
        std::this_thread::sleep_for(std::chrono::milliseconds(request.intervalMs));
        const std::vector<std::filesystem::path> changed = watch.poll();
        if (changed.empty()) {
            continue;
        }
        since = std::chrono::steady_clock::now();
        for (const std::filesystem::path& file : changed) {
            std::printf("changed: %s\n", file.string().c_str());
        }
        std::fflush(stdout);
        std::tie(files, ok) = load(request.project, command, batch);
        if (!ok) {
            std::printf("the project has errors: keeping the last images\n");
            std::fflush(stdout);
            startWatching(files, false);
            status = 1;
            continue;
        }
        status = renderAll(batch, request, since, statistics) ? 0 : 1;
        ++renders;
        startWatching(files, true);
    }
    std::signal(SIGINT, SIG_DFL);
    std::signal(SIGTERM, SIG_DFL);
    return status;
}

}  // namespace sylva::app
