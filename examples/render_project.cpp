// Example: render one view of a project through the library API, the way `sylva render`
// does, without the CLI. The project language (sylva_dsl) turns the file into one
// ProjectModel per scenario; render::BatchRenderer plans the project's view series (every
// job with a stable index), and renders the one job asked for.
//
//   sylva_example_render_project PROJECT CAMERA OUT_FOLDER [WIDTHxHEIGHT]
//
// Renders the first image of camera CAMERA (its first scenario and time) to the file the
// views block's output template names under OUT_FOLDER, and prints that file's path.
// Exit code 0 when the image was written.
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "sylva/dsl/ProjectLoader.h"
#include "sylva/render/batch/BatchRenderer.h"

namespace {

// Prints what the run reports: each file written, each error.
class Printer final : public sylva::render::BatchListener {
public:
    void jobDone(const sylva::render::JobReport& report) override {
        std::printf("%s  %dx%d\n", report.job->output.string().c_str(), report.width,
                    report.height);
    }
    void error(const std::string& message) override {
        std::fprintf(stderr, "render_project: %s\n", message.c_str());
    }
};

int fail(const std::string& message) {
    std::fprintf(stderr, "render_project: %s\n", message.c_str());
    return 1;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 4 || argc > 5) {
        std::fprintf(stderr,
                     "usage: sylva_example_render_project PROJECT CAMERA OUT_FOLDER "
                     "[WIDTHxHEIGHT]\n");
        return 2;
    }
    const std::string camera = argv[2];
    sylva::render::BatchOptions options;
    if (argc == 5 && std::sscanf(argv[4], "%dx%d", &options.width, &options.height) != 2) {
        return fail(std::string("size must be WIDTHxHEIGHT, got '") + argv[4] + "'");
    }

    // 1. The project as models: one per scenario (or the one model of a project without).
    sylva::dsl::LoadResult loaded = sylva::dsl::loadProject(argv[1]);
    if (loaded.hasErrors() || !loaded.model) {
        return fail(loaded.render());
    }
    std::vector<sylva::ProjectModel> scenarios = std::move(loaded.scenarios);
    if (scenarios.empty()) {
        scenarios.push_back(std::move(*loaded.model));
    }
    sylva::render::BatchRenderer batch(options);
    if (sylva::Status set = batch.setProject(std::move(scenarios)); !set) {
        return fail(set.error().message);
    }

    // 2. The job: the first image of the camera in the full job list.
    sylva::render::BatchSelection selection;
    selection.outputFolder = argv[3];
    selection.manifest = false;
    sylva::Result<sylva::render::RenderSetup> setup = batch.setup();
    if (!setup) {
        return fail(setup.error().message);
    }
    sylva::Result<sylva::render::BatchPlan> series =
        sylva::render::BatchPlan::make(batch.project(), setup.value(), selection);
    if (!series) {
        return fail(series.error().message);
    }
    for (const sylva::RenderJob& job : series->allJobs()) {
        if (job.kind == sylva::RenderJobKind::Image && job.camera == camera) {
            selection.range = sylva::render::JobRange{job.index, job.index};
            break;
        }
    }
    if (!selection.range) {
        return fail("no views block renders camera '" + camera + "'");
    }

    // 3. Render that job alone (the range), checking its output folder first.
    sylva::Result<sylva::render::BatchPlan> plan = batch.plan(selection);
    if (!plan) {
        return fail(plan.error().message);
    }
    Printer printer;
    sylva::Result<sylva::render::BatchSummary> summary = batch.run(plan.value(), printer);
    if (!summary) {
        return fail(summary.error().message);
    }
    return summary->failed == 0 && summary->degraded == 0 && summary->done == 1 ? 0 : 1;
}
