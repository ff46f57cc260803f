// `sylva assemble PROJECT [--out DIR] [--views NAME] [--size WxH] [-D name=value]`: the
// reduce step after a render farm ran the images (`render --jobs A-B`, shards, Slurm
// array tasks): the compare and blend images, the MP4s of path series and the contact
// sheets, made from the finished images on disk by render::SeriesAssembler, without a GL
// context. Every image must be current in the manifests of --out (any shard's or
// range's); otherwise nothing is made and the missing ones are named (exit code 1).
// Files that are already current are skipped, so assemble can run again. Exit codes: 0
// done, 1 images missing or a project or data error, 2 usage, 75 the disk is full.
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <string>

#include "CommandLine.h"
#include "Commands.h"
#include "ProjectSession.h"
#include "sylva/render/batch/BatchRenderer.h"
#include "sylva/render/batch/SeriesAssembler.h"

namespace sylva::app {
namespace {

// Prints each file written and each error; the image jobs only count as skipped.
class AssemblePrinter final : public render::BatchListener {
public:
    void jobDone(const render::JobReport& report) override {
        if (!report.skipped) {
            std::printf("%s  %.2f s\n", report.job->output.string().c_str(), report.seconds);
        }
    }
    void error(const std::string& message) override {
        if (message.find(std::strerror(ENOSPC)) != std::string::npos) {
            diskFull = true;
        }
        reportError(message);
    }
    void contactSheetWritten(const std::filesystem::path& file, std::size_t images) override {
        std::printf("%s  contact sheet of %zu images\n", file.string().c_str(), images);
    }
    bool diskFull = false;
};

// Whether every Image job of the plan is current; names up to five that are not.
bool imagesFinished(const render::BatchPlan& plan) {
    std::size_t missing = 0;
    std::string names;
    for (const RenderJob& job : plan.jobs()) {
        if (job.kind == RenderJobKind::Image && !plan.isCurrent(job)) {
            if (++missing <= 5) {
                names += (names.empty() ? "" : ", ") + plan.relativeOutput(job.output) + " (job " +
                         std::to_string(job.index) + ")";
            }
        }
    }
    if (missing > 0) {
        reportError("assemble: " + std::to_string(missing) +
                    " images are not rendered (or not current): " + names +
                    (missing > 5 ? ", ..." : "") +
                    "; render them first (sylva render --resume, or the farm's --jobs ranges)");
    }
    return missing == 0;
}

}  // namespace

int runAssemble(const std::vector<std::string>& arguments) {
    const ParsedCommandLine command =
        parseCommandLine(arguments, {{"out"}, {"views"}, {"size"}, {"help", false}});
    if (command.has("help")) {
        std::puts(
            "usage: sylva assemble PROJECT [--out DIR] [--views NAME] [--size WxH] [-D "
            "name=value]\n"
            "Makes the comparisons, videos and contact sheets from the finished images in --out\n"
            "(no GL). Every image must be current in the manifests there.");
        return 0;
    }
    if (!command.error.empty() || command.positional.size() != 1) {
        reportError(command.error.empty()
                        ? "assemble needs exactly one project file (see 'sylva assemble --help')"
                        : command.error);
        return 2;
    }
    render::BatchOptions options;
    if (std::optional<std::string> size = command.get("size");
        size && !parseSize(*size, options.width, options.height)) {
        reportError("--size expects WIDTHxHEIGHT within 1..16384, got '" + *size + "'");
        return 2;
    }
    dsl::LoadResult loaded = dsl::loadProject(command.positional[0], loadOptionsFor(command));
    printDiagnostics(loaded);
    if (loaded.hasErrors() || !loaded.model) {
        return 1;
    }
    render::BatchRenderer batch(options);
    if (Status set = batch.setProject(scenarioModels(std::move(loaded))); !set) {
        reportError(set.error().message);
        return 1;
    }
    render::BatchSelection selection;
    selection.outputFolder = command.get("out").value_or("out");
    selection.views = command.get("views").value_or("");
    selection.resume = true;  // reads every manifest in --out
    Result<render::BatchPlan> plan = batch.plan(selection);
    if (!plan) {
        reportError(plan.error().message);
        return 1;
    }
    if (!imagesFinished(plan.value())) {
        return 1;
    }
    AssemblePrinter printer;
    render::BatchRun run(plan.value(), printer);
    for (const RenderJob& job : plan->jobs()) {
        if (job.kind == RenderJobKind::Image) {
            (void)run.skipIfCurrent(job);
        }
    }
    render::SeriesAssembler assembler(run);
    assembler.assemble();
    assembler.writeContactSheets();
    const render::BatchSummary summary = run.summary();
    if (summary.failed > 0) {
        reportError(std::to_string(summary.failed) + " of " + std::to_string(summary.total) +
                    " files could not be made");
        return printer.diskFull ? 75 : 1;
    }
    return 0;
}

}  // namespace sylva::app
