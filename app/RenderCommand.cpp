// `sylva render PROJECT [--views NAME] [--out DIR] [--size WxH] [--gl egl|osmesa|glfw]
//                       [--resume] [--shard i/N] [--progress auto|json|plain] [--cache-mb N]
//                       [--no-comparisons] [-D name=value]`
// Renders the view series of the project (or of one views block) through
// render::BatchRenderer: cameras and path frames × scenarios × times (the sun from each
// time, NOAA), then the compare/blend images, the MP4s of path series (frames encoded by
// ffmpeg) and a contact sheet per series. PNG outputs are 8-bit sRGB, EXR outputs linear
// half-float radiance (after exposure, before tone mapping); both carry metadata (camera,
// scenario, time, project, hashes, version). Every file is written atomically and
// recorded in a manifest; --resume skips images whose record matches; Ctrl-C stops after
// the current image. Exit code 0 only when every image was written.
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <csignal>
#include <cstdio>
#include <optional>
#include <string>

#include "CommandLine.h"
#include "Commands.h"
#include "ProjectSession.h"
#include "sylva/render/batch/BatchRenderer.h"

namespace sylva::app {
namespace {

std::atomic<bool> interrupted{false};

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

void printUsage() {
    std::puts(
        "usage: sylva render PROJECT [--views NAME] [--out DIR] [--size WxH] [--gl "
        "egl|osmesa|glfw]\n"
        "                    [--resume] [--shard i/N] [--progress auto|json|plain] [--cache-mb "
        "N]\n"
        "                    [--no-comparisons] [-D name=value]\n"
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
    if (std::optional<std::string> text = command.get("shard")) {
        Result<std::pair<int, int>> parsed = ViewSeries::parseShard(*text);
        if (!parsed) {
            reportError(parsed.error().message);
            return false;
        }
        request.selection.shard = parsed.value();
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

}  // namespace

int runRender(const std::vector<std::string>& arguments) {
    const ParsedCommandLine command = parseCommandLine(arguments, {{"views"},
                                                                   {"out"},
                                                                   {"size"},
                                                                   {"gl"},
                                                                   {"shard"},
                                                                   {"progress"},
                                                                   {"cache-mb"},
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
    dsl::LoadResult loaded = dsl::loadProject(request.project, loadOptionsFor(command));
    printDiagnostics(loaded);
    if (loaded.hasErrors() || !loaded.model) {
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
    if (!summary) {
        reportError(summary.error().message);
        return 1;
    }
    return finish(summary.value(), request.progressJson);
}

}  // namespace sylva::app
