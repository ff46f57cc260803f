// `sylva jobs PROJECT [--json] [--out DIR] [--views NAME] [--size WxH] [-D name=value]`:
// the series' jobs for a render farm, without GL and without writing anything: each job's
// stable index (what `sylva render --jobs A-B` takes), kind, view, camera or path frame,
// scenario, time, group (the viewpoint-and-time group that shards keep together), output
// (relative to --out), content hash, an estimated cost and its state against the
// manifests in --out (this run's and every shard's and range's): current (recorded with
// this hash, file present), stale (recorded with another hash, or the file is gone) or
// missing. --size must match the render's, since it is part of every hash.
//
// Cost: relative units, the megapixels a job makes (images at the render size; compare
// and blend images 0.05 of that, composed on the CPU from finished images; videos 0.02 per
// frame, encoding). It is meant for cutting the series into chunks, not as seconds: a
// cold image costs far more than a later time of the same camera (docs/farms.md).
// Exit codes: 0, 1 project error, 2 usage.
#include <cstdio>
#include <string>

#include "CommandLine.h"
#include "Commands.h"
#include "ProjectSession.h"
#include "sylva/render/batch/BatchRenderer.h"

namespace sylva::app {
namespace {

std::string jsonText(const std::string& text) {
    std::string out = "\"";
    for (char c : text) {
        if (c == '"' || c == '\\') {
            out += '\\';
        }
        if (static_cast<unsigned char>(c) >= 0x20) {
            out += c;
        }
    }
    return out + "\"";
}

const char* stateName(render::BatchPlan::RecordState state) {
    switch (state) {
        case render::BatchPlan::RecordState::Current:
            return "current";
        case render::BatchPlan::RecordState::Stale:
            return "stale";
        case render::BatchPlan::RecordState::Missing:
            break;
    }
    return "missing";
}

double costOf(const RenderJob& job, const render::RenderSetup& setup) {
    const double megapixels = static_cast<double>(setup.settings.width) *
                              static_cast<double>(setup.settings.height) / 1e6;
    switch (job.kind) {
        case RenderJobKind::Image:
            return megapixels;
        case RenderJobKind::Compare:
        case RenderJobKind::Blend:
            return 0.05 * megapixels;
        case RenderJobKind::Video:
            return 0.02 * megapixels * static_cast<double>(job.frames.size());
    }
    return megapixels;
}

void printJson(const render::BatchPlan& plan, const std::filesystem::path& project) {
    std::size_t groups = 0, current = 0, stale = 0;
    std::printf("{\"project\": %s, \"out\": %s, \"jobs\": [\n", jsonText(project.string()).c_str(),
                jsonText(plan.selection().outputFolder.string()).c_str());
    const std::vector<RenderJob>& jobs = plan.allJobs();
    for (std::size_t i = 0; i < jobs.size(); ++i) {
        const RenderJob& job = jobs[i];
        const ManifestEntry entry = plan.entryFor(job);
        const render::BatchPlan::RecordState state = plan.recordState(job);
        groups = std::max(groups, job.group + 1);
        current += state == render::BatchPlan::RecordState::Current ? 1 : 0;
        stale += state == render::BatchPlan::RecordState::Stale ? 1 : 0;
        char hash[17];
        std::snprintf(hash, sizeof hash, "%016llx",
                      static_cast<unsigned long long>(plan.hashOf(job)));
        std::printf(
            "  {\"index\": %zu, \"kind\": \"%s\", \"view\": %s, \"camera\": %s, \"path\": %s, "
            "\"frame\": %d, \"scenario\": %s, \"time\": %s, \"group\": %zu, \"output\": %s, "
            "\"hash\": \"%s\", \"cost\": %.6g, \"state\": \"%s\"}%s\n",
            job.index, render::BatchPlan::kindName(job.kind).c_str(), jsonText(job.view).c_str(),
            jsonText(job.camera).c_str(), jsonText(job.path).c_str(), job.frame,
            jsonText(job.scenario).c_str(), jsonText(entry.time).c_str(), job.group,
            jsonText(plan.relativeOutput(job.output)).c_str(), hash, costOf(job, plan.setup()),
            stateName(state), i + 1 < jobs.size() ? "," : "");
    }
    std::printf(
        "], \"total\": %zu, \"groups\": %zu, \"current\": %zu, \"stale\": %zu, \"missing\": "
        "%zu}\n",
        jobs.size(), groups, current, stale, jobs.size() - current - stale);
}

void printText(const render::BatchPlan& plan) {
    for (const RenderJob& job : plan.allJobs()) {
        std::printf("%5zu  %-7s  group %-4zu  %-8s  %s\n", job.index,
                    render::BatchPlan::kindName(job.kind).c_str(), job.group,
                    stateName(plan.recordState(job)), plan.relativeOutput(job.output).c_str());
    }
}

}  // namespace

int runJobs(const std::vector<std::string>& arguments) {
    const ParsedCommandLine command = parseCommandLine(
        arguments, {{"json", false}, {"out"}, {"views"}, {"size"}, {"help", false}});
    if (command.has("help")) {
        std::puts(
            "usage: sylva jobs PROJECT [--json] [--out DIR] [--views NAME] [--size WxH] "
            "[-D name=value]\n"
            "Lists the series' jobs: index (for render --jobs A-B), kind, group, output, hash,\n"
            "estimated cost and state (current, stale, missing) against the manifests in --out.");
        return 0;
    }
    if (!command.error.empty() || command.positional.size() != 1) {
        reportError(command.error.empty()
                        ? "jobs needs exactly one project file (see 'sylva jobs --help')"
                        : command.error);
        return 2;
    }
    render::BatchOptions options;
    if (std::optional<std::string> size = command.get("size");
        size && !parseSize(*size, options.width, options.height)) {
        reportError("--size expects WIDTHxHEIGHT within 1..16384, got '" + *size + "'");
        return 2;
    }
    const std::filesystem::path project = command.positional[0];
    dsl::LoadResult loaded = dsl::loadProject(project, loadOptionsFor(command));
    printDiagnostics(loaded);
    if (loaded.hasErrors() || !loaded.model) {
        return 1;
    }
    render::BatchRenderer batch(options);
    if (Status set = batch.setProject(scenarioModels(std::move(loaded))); !set) {
        reportError(set.error().message);
        return 1;
    }
    Result<render::RenderSetup> setup = batch.setup();
    if (!setup) {
        reportError(setup.error().message);
        return 1;
    }
    render::BatchSelection selection;
    selection.outputFolder = command.get("out").value_or("out");
    selection.views = command.get("views").value_or("");
    selection.resume = true;
    // BatchPlan::make and loadManifest only: no folder is created, nothing is written.
    Result<render::BatchPlan> plan =
        render::BatchPlan::make(batch.project(), setup.value(), selection);
    if (!plan) {
        reportError(plan.error().message);
        return 1;
    }
    if (Status manifest = plan->loadManifest(); !manifest) {
        reportError(manifest.error().message);
        return 1;
    }
    if (command.has("json")) {
        printJson(plan.value(), project);
    } else {
        printText(plan.value());
    }
    return 0;
}

}  // namespace sylva::app
