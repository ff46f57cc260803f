// `sylva render PROJECT [--views NAME] [--out DIR] [--size WxH] [--gl egl|osmesa|glfw]
//                       [--resume] [--shard i/N | --jobs A-B] [--progress auto|json|plain]
//                       [--cache-mb N]
//                       [--no-comparisons] [--disk-cache DIR | --no-disk-cache]
//                       [--disk-cache-mb N] [-D name=value]`
// Renders the view series of the project (or of one views block) through
// render::BatchRenderer: cameras and path frames × scenarios × times (the sun from each
// time, NOAA), then the compare/blend images, the MP4s of path series (frames encoded by
// ffmpeg) and a contact sheet per series. PNG outputs are 8-bit sRGB, EXR outputs linear
// half-float radiance (after exposure, before tone mapping); both carry metadata (camera,
// scenario, time, project, hashes, version). Every file is written atomically and
// recorded in a manifest; --resume skips images whose record matches; Ctrl-C stops after
// the current image. Exit codes: 0 every image written, 1 a project or data error (a
// farm should not retry), 2 usage, 75 transient (disk full, no GL context: retry with
// --resume), 130 interrupted. --jobs A-B and Slurm array tasks: see farmSelection.
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>

#include "CommandLine.h"
#include "Commands.h"
#include "PhotoDeliverables.h"
#include "ProjectSession.h"
#include "TileStatisticsReport.h"
#include "sylva/core/model/BlockReader.h"
#include "sylva/render/batch/BatchRenderer.h"

namespace sylva::app {
namespace {

std::atomic<bool> interrupted{false};

// EX_TEMPFAIL of sysexits.h: a render farm retries the task.
constexpr int kExitTransient = 75;

void onInterrupt(int) {
    interrupted.store(true);
}

std::string jsonText(const std::string& text) {
    std::string out = "\"";
    for (char c : text) {
        if (c == '"' || c == '\\') {
            out += '\\';
        }
        out += c;
    }
    return out + "\"";
}

// What the command line asks for.
struct RenderRequest {
    std::filesystem::path project;
    render::BatchOptions options;
    render::BatchSelection selection;
    bool progressJson = false;  // --progress json: one JSON line per event on stdout
    bool progressBar = false;   // --progress auto on a terminal: a bar on stderr
};

// Prints a run the way `sylva render` reports it: a line per file written (stdout;
// not with JSON progress), errors as "sylva: ..." (stderr), then the progress.
class RenderPrinter final : public render::BatchListener {
public:
    RenderPrinter(bool json, bool bar) : json_(json), bar_(bar) {}

    void jobDone(const render::JobReport& report) override {
        if (!report.skipped && !json_) {
            printFile(report);
        }
        printProgress(report);
    }
    void error(const std::string& message) override { reportError(message); }
    void contactSheetWritten(const std::filesystem::path& file, std::size_t images) override {
        if (!json_) {
            std::printf("%s  contact sheet of %zu images\n", file.string().c_str(), images);
        }
    }

private:
    static void printFile(const render::JobReport& report) {
        const RenderJob& job = *report.job;
        const std::string file = job.output.string();
        const char* output = file.c_str();
        switch (job.kind) {
            case RenderJobKind::Video:
                std::printf("%s  %zu frames at %g fps  %.2f s\n", output, job.frames.size(),
                            job.framesPerSecond, report.seconds);
                break;
            case RenderJobKind::Compare:
            case RenderJobKind::Blend:
                std::printf("%s  %dx%d  %.2f s  (%s of %s and %s)\n", output, report.width,
                            report.height, report.seconds,
                            render::BatchPlan::kindName(job.kind).c_str(),
                            report.firstScenario.c_str(), report.secondScenario.c_str());
                break;
            case RenderJobKind::Image:
                std::printf("%s  %dx%d  %.2f s  (levels %d-%d, %llu triangles, %zu tiles)\n",
                            output, report.width, report.height, report.seconds,
                            report.levels.coarsest, report.levels.finest,
                            static_cast<unsigned long long>(report.triangles), report.tiles);
                break;
        }
        std::fflush(stdout);
    }

    void printProgress(const render::JobReport& report) const {
        if (json_) {
            std::printf(
                "{\"event\": \"image\", \"index\": %zu, \"total\": %zu, \"output\": %s, \"kind\": "
                "\"%s\", "
                "\"skipped\": %s, \"seconds\": %.3f, \"tiles\": %zu, \"eta_s\": %.1f}\n",
                report.done, report.total, jsonText(report.job->output.string()).c_str(),
                render::BatchPlan::kindName(report.job->kind).c_str(),
                report.skipped ? "true" : "false", report.seconds, report.tiles, report.etaSeconds);
            std::fflush(stdout);
            return;
        }
        if (bar_) {
            const int width = 30;
            const int filled =
                static_cast<int>(width * report.done / std::max<std::size_t>(report.total, 1));
            std::fprintf(stderr, "\r[%s%s] %zu/%zu  ETA %4.0f s  ",
                         std::string(static_cast<std::size_t>(filled), '#').c_str(),
                         std::string(static_cast<std::size_t>(width - filled), '.').c_str(),
                         report.done, report.total, report.etaSeconds);
            if (report.done == report.total) {
                std::fputc('\n', stderr);
            }
            std::fflush(stderr);
        }
    }

    bool json_;
    bool bar_;
};

// "A-B" or "A" (job indices of `sylva jobs`, both included, A <= B).
Result<render::JobRange> parseJobRange(const std::string& text) {
    unsigned long long first = 0, last = 0;
    char dash = 0, rest = 0;
    const int fields = std::sscanf(text.c_str(), "%llu%c%llu%c", &first, &dash, &last, &rest);
    const bool single = fields == 1 && text.find_first_not_of("0123456789") == std::string::npos;
    if (single) {
        last = first;
    }
    if (!(single || (fields == 3 && dash == '-' && text.find_first_of("+ ") == std::string::npos &&
                     text[0] != '-')) ||
        first > last || last > 1000000000ull) {
        return Error{"--jobs expects A-B with 0 <= A <= B (job indices from 'sylva jobs'), got '" +
                     text + "'"};
    }
    return render::JobRange{static_cast<std::size_t>(first), static_cast<std::size_t>(last)};
}

// A whole number from the environment, or nullopt when unset or not a number.
std::optional<long long> environmentNumber(const char* name) {
    const char* text = std::getenv(name);
    if (text == nullptr || *text == '\0') {
        return std::nullopt;
    }
    char* end = nullptr;
    const long long value = std::strtoll(text, &end, 10);
    return *end == '\0' ? std::optional<long long>(value) : std::nullopt;
}

// --jobs A-B, --shard i/N, or (neither given) a Slurm array task: task i of
// SLURM_ARRAY_TASK_COUNT (counted from SLURM_ARRAY_TASK_MIN by SLURM_ARRAY_TASK_STEP)
// renders shard i/N. A range renders only images (comparisons, videos and contact
// sheets are `sylva assemble`'s) and ends at the last job when it reaches past it.
Status farmSelection(const ParsedCommandLine& command, render::BatchSelection& selection) {
    if (std::optional<std::string> text = command.get("jobs")) {
        if (command.has("shard")) {
            return Error{"--jobs and --shard exclude each other"};
        }
        Result<render::JobRange> range = parseJobRange(*text);
        if (!range) {
            return range.error();
        }
        selection.range = range.value();
        selection.clampRange = true;
        selection.imagesOnly = true;
        return {};
    }
    if (std::optional<std::string> text = command.get("shard")) {
        Result<std::pair<int, int>> parsed = ViewSeries::parseShard(*text);
        if (!parsed) {
            return parsed.error();
        }
        selection.shard = parsed.value();
        return {};
    }
    const std::optional<long long> task = environmentNumber("SLURM_ARRAY_TASK_ID");
    if (!task) {
        return {};
    }
    const std::optional<long long> count = environmentNumber("SLURM_ARRAY_TASK_COUNT");
    const long long minimum = environmentNumber("SLURM_ARRAY_TASK_MIN").value_or(0);
    const long long step = std::max(1LL, environmentNumber("SLURM_ARRAY_TASK_STEP").value_or(1));
    const long long index = (*task - minimum) / step + 1;
    if (!count || *count < 1 || index < 1 || index > *count || *count > 1000000) {
        return Error{"SLURM_ARRAY_TASK_ID=" + std::to_string(*task) +
                     " with SLURM_ARRAY_TASK_COUNT=" + (count ? std::to_string(*count) : "unset") +
                     " and SLURM_ARRAY_TASK_MIN=" + std::to_string(minimum) +
                     " is no task of the array; pass --shard i/N or --jobs A-B instead"};
    }
    selection.shard = {static_cast<int>(index), static_cast<int>(*count)};
    std::fprintf(stderr, "sylva: Slurm array task %lld: shard %lld/%lld\n", *task, index, *count);
    return {};
}

void printUsage() {
    std::puts(
        "usage: sylva render PROJECT [--views NAME] [--out DIR] [--size WxH] [--gl "
        "egl|osmesa|glfw]\n"
        "                    [--resume] [--shard i/N | --jobs A-B] [--progress auto|json|plain]\n"
        "                    [--cache-mb N]\n"
        "                    [--no-comparisons] [--disk-cache DIR | --no-disk-cache]\n"
        "                    [--disk-cache-mb N] [--tile-stats] [-D name=value]\n"
        "The disk tile cache (shared by processes and machines) is on by default: --disk-cache,\n"
        "else render { disk_cache }, else $SYLVA_CACHE_DIR/tiles, $XDG_CACHE_HOME/sylva/tiles or\n"
        "~/.cache/sylva/tiles.\n"
        "--jobs A-B renders the images among jobs A..B of 'sylva jobs' (ending at the last job);\n"
        "without --jobs and --shard, SLURM_ARRAY_TASK_ID/COUNT select shard i/N. Exit codes: 0\n"
        "done, 1 project or data error (do not retry), 2 usage, 75 transient (disk full, no GL\n"
        "context: retry, with --resume).\n"
        "Outputs by the views' template extension: .png (8-bit sRGB), .exr (linear radiance,\n"
        "half float), .mp4 (path frames encoded by ffmpeg). --no-comparisons renders only the\n"
        "scenario images (no compare/blend images, no contact sheets).");
}

// Fills `request` from the options; false after reporting a usage error.
bool parseRequest(const ParsedCommandLine& command, RenderRequest& request) {
    if (!command.error.empty() || command.positional.size() != 1) {
        reportError(command.error.empty()
                        ? "render needs exactly one project file (see 'sylva render --help')"
                        : command.error);
        return false;
    }
    request.project = command.positional[0];
    if (std::optional<std::string> size = command.get("size");
        size && !parseSize(*size, request.options.width, request.options.height)) {
        reportError("--size expects WIDTHxHEIGHT within 1..16384, got '" + *size + "'");
        return false;
    }
    Result<std::optional<render::GlBackend>> backend = glBackendOption(command);
    if (!backend) {
        reportError(backend.error().message);
        return false;
    }
    request.options.backend = backend.value();
    const Result<std::optional<std::size_t>> cache = cacheMegabytesOption(command);
    if (!cache) {
        reportError(cache.error().message);
        return false;
    }
    request.options.cacheMegabytes = cache.value();
    if (Status disk =
            diskCacheOptions(command, request.options.diskCacheDisabled,
                             request.options.diskCacheFolder, request.options.diskCacheMegabytes);
        !disk) {
        reportError(disk.error().message);
        return false;
    }
    request.options.diskCacheByDefault = true;
    request.options.warningSink = [](const std::string& message) {
        std::fprintf(stderr, "sylva: warning: %s\n", message.c_str());
    };
    if (Status farm = farmSelection(command, request.selection); !farm) {
        reportError(farm.error().message);
        return false;
    }
    const std::string progress = command.get("progress").value_or("auto");
    if (progress != "auto" && progress != "json" && progress != "plain") {
        reportError("--progress expects auto, json or plain, got '" + progress + "'");
        return false;
    }
    request.progressJson = progress == "json";
    request.progressBar = progress == "auto" && ::isatty(STDERR_FILENO);
    request.selection.resume = command.has("resume");
    request.selection.comparisons = !command.has("no-comparisons");
    request.selection.outputFolder = command.get("out").value_or("out");
    request.selection.views = command.get("views").value_or("");
    return true;
}

// The exit status of a finished (or cancelled) run, after printing its end.
int finish(const render::BatchSummary& summary, bool progressJson) {
    if (summary.cancelled) {
        reportError("interrupted: " + std::to_string(summary.done) + " of " +
                    std::to_string(summary.total) +
                    " images done; run again with --resume to finish");
        return 130;
    }
    if (progressJson) {
        std::printf(
            "{\"event\": \"done\", \"total\": %zu, \"skipped\": %d, \"failed\": %d, \"degraded\": "
            "%d}\n",
            summary.total, summary.skipped, summary.failed, summary.degraded);
    }
    if (summary.transientFailures > 0) {
        reportError("stopped after a transient failure (" + std::to_string(summary.failed) +
                    " of " + std::to_string(summary.total) +
                    " images not written); run again with --resume to continue");
        return kExitTransient;
    }
    if (summary.failed > 0) {
        reportError(std::to_string(summary.failed) + " of " + std::to_string(summary.total) +
                    " images could not be rendered");
        return 1;
    }
    if (summary.degraded > 0) {
        reportError(std::to_string(summary.degraded) + " of " + std::to_string(summary.total) +
                    " images were rendered with missing data");
        return 1;
    }
    return 0;
}

// The photo blocks the selected views blocks name in `photos` (all views blocks without
// --views), in the order named, each once.
std::vector<std::string> photosOfViews(const ProjectModel& model, const std::string& only) {
    std::vector<std::string> names;
    for (const Block& views : model.views) {
        if (!only.empty() && views.name != only) {
            continue;
        }
        BlockReader reader(views, SchemaRegistry::builtin().find("views"));
        for (const std::string& name : reader.references("photos")) {
            if (std::find(names.begin(), names.end(), name) == names.end()) {
                names.push_back(name);
            }
        }
    }
    return names;
}

}  // namespace

int runRender(const std::vector<std::string>& arguments) {
    const ParsedCommandLine command = parseCommandLine(arguments, {{"views"},
                                                                   {"out"},
                                                                   {"size"},
                                                                   {"gl"},
                                                                   {"shard"},
                                                                   {"jobs"},
                                                                   {"progress"},
                                                                   {"cache-mb"},
                                                                   {"disk-cache"},
                                                                   {"disk-cache-mb"},
                                                                   {"no-disk-cache", false},
                                                                   {"tile-stats", false},
                                                                   {"resume", false},
                                                                   {"no-comparisons", false},
                                                                   {"help", false}});
    if (command.has("help")) {
        printUsage();
        return 0;
    }
    RenderRequest request;
    if (!parseRequest(command, request)) {
        return 2;
    }
    // A misspelt SYLVA_GL is a configuration error (exit 1), not a GL context that failed
    // on this node (exit 75, retried elsewhere): check it before rendering.
    if (const char* gl = std::getenv("SYLVA_GL"); gl && *gl && !request.options.backend) {
        if (Result<render::GlBackend> parsed = render::parseBackend(gl); !parsed) {
            reportError("SYLVA_GL: " + parsed.error().message);
            return 1;
        }
    }
    dsl::LoadResult loaded = dsl::loadProject(request.project, loadOptionsFor(command));
    printDiagnostics(loaded);
    if (loaded.hasErrors() || !loaded.model) {
        return 1;
    }
    // The views' photo blocks (`views { photos = [...] }`) are read with their photographs
    // now, so a bad one stops the command before anything renders; they are made after a
    // run that rendered the whole series (not a shard or a job range) without failures.
    const std::vector<std::string> photoNames =
        photosOfViews(*loaded.model, request.selection.views);
    std::optional<std::vector<PlannedPhoto>> photos =
        photoNames.empty() ? std::optional<std::vector<PlannedPhoto>>(std::vector<PlannedPhoto>{})
                           : planPhotos(*loaded.model, photoNames, false);
    if (!photos) {
        return 1;
    }
    render::BatchRenderer batch(request.options);
    if (Status set = batch.setProject(scenarioModels(std::move(loaded))); !set) {
        reportError(set.error().message);
        return 1;
    }
    // Every job, its output path and every check that can fail, before anything renders.
    Result<render::BatchPlan> plan = batch.plan(request.selection);
    if (!plan) {
        reportError(plan.error().message);
        return 1;
    }
    RenderPrinter printer(request.progressJson, request.progressBar);
    std::signal(SIGINT, onInterrupt);
    std::signal(SIGTERM, onInterrupt);
    Result<render::BatchSummary> summary = batch.run(plan.value(), printer, &interrupted);
    std::signal(SIGINT, SIG_DFL);
    std::signal(SIGTERM, SIG_DFL);
    if (command.has("tile-stats")) {
        TileStatisticsReport().print(batch.scheduler(plan->setup()), stderr);
    }
    if (!summary) {
        // Only a renderer that cannot be made (no GL context on this node) ends a run here.
        reportError(summary.error().message);
        return kExitTransient;
    }
    const int status = finish(summary.value(), request.progressJson);
    if (status != 0 || photos->empty() || !plan->wholeSeries()) {
        return status;
    }
    nlohmann::ordered_json summaries = nlohmann::ordered_json::array();
    return makePhotos(batch, *photos, request.selection.outputFolder, summaries) ? 0 : 1;
}

}  // namespace sylva::app
