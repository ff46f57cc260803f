// BatchRenderer: renders a project's view series as files — the last stage of the
// pipeline (jobs → images → comparisons → videos → contact sheets → manifest) as a
// library, used by `sylva render`, `sylva watch`, the example program and the tests.
//
// It takes the project as plain models (one ProjectModel per scenario, as the DSL makes
// them; it never parses project files) and owns what lives across runs: the scenarios'
// source graphs, one Scheduler whose tile cache all scenarios share (sources with equal
// content hashes share tiles), the GL context and the SceneRenderer (both created at the
// first image, so a run that only assembles or skips needs no GL).
//
// A run is: plan() (BatchPlan: every job with a stable index, this run's selection in
// render order, hashes, the manifest, the output checks), then run(): the image phase
// (renderImages: each Image job's camera and sun from JobView, rendered with every
// wanted tile waited for, so images do not depend on thread timing, written atomically
// with metadata) and the assemble phase (SeriesAssembler: comparisons, videos, contact
// sheets from the finished images). Progress and every message go to a BatchListener;
// nothing is printed here. Cancellation: BatchRun.
//
// Errors: a job that fails is reported and counted (BatchSummary), the run goes on; only
// a missing GL context or renderer ends a run early (run() returns that error).
// Thread: one thread, the one that owns the GL context.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "sylva/core/base/Result.h"
#include "sylva/core/model/ProjectModel.h"
#include "sylva/core/scheduler/Scheduler.h"
#include "sylva/core/sources/graph/ScenarioGraphs.h"
#include "sylva/render/batch/BatchListener.h"
#include "sylva/render/batch/BatchPlan.h"
#include "sylva/render/batch/BatchRun.h"
#include "sylva/render/batch/RenderSetup.h"
#include "sylva/render/gl/GlContext.h"
#include "sylva/render/gl/ShaderLibrary.h"
#include "sylva/render/scene/SceneRenderer.h"

namespace sylva::render {

struct BatchOptions {
    int width = 0;  // > 0 (both): instead of the render block's resolution (--size)
    int height = 0;
    std::optional<GlBackend> backend;           // GL back end (ContextOptions::backend)
    std::optional<std::size_t> cacheMegabytes;  // tile cache budget, else render { cache_mb }
    // A visible window of the size above (the viewer) instead of an off-screen context;
    // with the GLFW back end only (others ignore it).
    bool visibleWindow = false;
    std::string windowTitle = "Sylva";
    // The disk tile cache folder: `diskCacheDisabled` (--no-disk-cache) wins, then
    // `diskCacheFolder` (--disk-cache), then the render block's disk_cache, then, when
    // `diskCacheByDefault` (the CLI), DiskTileCache::defaultFolder(); else none.
    bool diskCacheDisabled = false;
    std::optional<std::filesystem::path> diskCacheFolder;
    bool diskCacheByDefault = false;
    std::optional<std::uint64_t> diskCacheMegabytes;  // else render { disk_cache_mb }
    // Receives the disk cache's warnings (unwritable folder, corrupt entry), each kind
    // once per process; from any thread.
    std::function<void(const std::string&)> warningSink;
    // SchedulerOptions::taskSink of the scheduler it creates (traces); none by default.
    std::function<void(const SchedulerTaskReport&)> schedulerTaskSink;
};

class BatchRenderer {
public:
    explicit BatchRenderer(BatchOptions options = {});
    ~BatchRenderer();
    BatchRenderer(const BatchRenderer&) = delete;
    BatchRenderer& operator=(const BatchRenderer&) = delete;

    // The project: one model per scenario in the project's order, the first being the
    // default (a project without scenarios: one model with an empty scenario name).
    // Builds the default scenario's graph (the others on first use). When a project was
    // set before (watch), every scenario's graph is built and the Scheduler keeps only
    // the tiles of sources whose content hash still exists, so an edit recomputes only
    // the changed branches. On error (located at the offending attribute) the previous
    // project stays. Plans made before are invalid afterwards.
    Status setProject(std::vector<ProjectModel> scenarios);
    bool hasProject() const { return project_.has_value(); }
    ScenarioGraphs& project();  // SYLVA_CHECK(hasProject())

    // The current project's render setup with the options applied.
    Result<RenderSetup> setup() const;
    // BatchPlan::make with setup(), then BatchPlan::prepareOutputs (ffmpeg, output
    // folders, manifest): every check that can fail before the first image.
    Result<BatchPlan> plan(const BatchSelection& selection);

    // Runs the plan: renderImages, then the assemble phase (SeriesAssembler::assemble and,
    // unless cancelled, writeContactSheets). Fails only when GL cannot render at all.
    Result<BatchSummary> run(BatchPlan& plan, BatchListener& listener,
                             const std::atomic<bool>* cancel = nullptr);
    // The image phase alone: every Image job of the run's plan, in plan order.
    Status renderImages(BatchRun& run);

    // Creates the GL context now (else at the first image), e.g. to fail before loading.
    Status createContext();
    // For a viewer that shows the jobs of a plan itself (JobView::forJob with
    // plan.layersOf and plan.pathOf, then SceneRenderer::render): the renderer and the
    // tile scheduler, created on first use with `setup`'s terrain settings and budget.
    Result<SceneRenderer*> sceneRenderer(const RenderSetup& setup);
    Scheduler& scheduler(const RenderSetup& setup);
    // The GL context (null before createContext or the first image).
    GlContext* context() { return context_.get(); }

private:
    // `keepDepth`: the job's depth buffer goes to the run for a wireline comparison.
    Status renderImage(BatchRun& run, const RenderJob& job, bool keepDepth);

    BatchOptions options_;
    // Declared so that they are destroyed in a safe order: the scheduler (its tasks name
    // sources) and the renderer (GL objects, while the context is current) go before the
    // context and the project's graphs.
    std::optional<ScenarioGraphs> project_;
    std::unique_ptr<GlContext> context_;
    ShaderLibrary library_;
    std::unique_ptr<SceneRenderer> renderer_;
    std::unique_ptr<Scheduler> scheduler_;
};

}  // namespace sylva::render
