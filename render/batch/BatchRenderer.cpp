#include "sylva/render/batch/BatchRenderer.h"

#include <chrono>
#include <utility>

#include "sylva/core/base/Check.h"
#include "sylva/render/batch/ImageOutput.h"
#include "sylva/render/batch/JobView.h"
#include "sylva/render/batch/SeriesAssembler.h"
#include "sylva/render/batch/ViewpointOutput.h"
#include "sylva/render/scene/PanoramaRenderer.h"

namespace sylva::render {

BatchRenderer::BatchRenderer(BatchOptions options) : options_(std::move(options)) {}

BatchRenderer::~BatchRenderer() = default;

Status BatchRenderer::setProject(std::vector<ProjectModel> scenarios) {
    Result<ScenarioGraphs> graphs = ScenarioGraphs::build(std::move(scenarios));
    if (!graphs) {
        return graphs.error();
    }
    if (project_) {
        // Build the new graphs, keep the tiles of unchanged sources, then let the old
        // graphs go (retainOnly waits for running tasks of dropped sources). A scenario
        // whose graph fails is reported when a plan needs it.
        (void)graphs->buildAll();
        if (scheduler_) {
            scheduler_->retainOnly(graphs->contentHashes());
        }
    }
    project_ = std::move(graphs.value());
    return {};
}

ScenarioGraphs& BatchRenderer::project() {
    SYLVA_CHECK(project_.has_value());
    return *project_;
}

Result<RenderSetup> BatchRenderer::setup() const {
    SYLVA_CHECK(project_.has_value());
    Result<RenderSetup> setup =
        RenderSetup::fromModel(project_->defaultModel(), options_.width, options_.height);
    if (setup && options_.cacheMegabytes) {
        setup->cacheMegabytes = *options_.cacheMegabytes;
    }
    return setup;
}

Result<BatchPlan> BatchRenderer::plan(const BatchSelection& selection) {
    Result<RenderSetup> setup = this->setup();
    if (!setup) {
        return setup.error();
    }
    Result<BatchPlan> plan = BatchPlan::make(project(), setup.value(), selection);
    if (!plan) {
        return plan.error();
    }
    if (Status prepared = plan->prepareOutputs(); !prepared) {
        return prepared.error();
    }
    return plan;
}

Status BatchRenderer::createContext() {
    if (context_) {
        return {};
    }
    ContextOptions contextOptions;
    contextOptions.backend = options_.backend;
    Result<std::unique_ptr<GlContext>> created = GlContext::create(contextOptions);
    if (!created) {
        return created.error();
    }
    context_ = std::move(created.value());
    return {};
}

Result<SceneRenderer*> BatchRenderer::sceneRenderer(const RenderSetup& setup) {
    if (Status context = createContext(); !context) {
        return context.error();
    }
    if (!renderer_) {
        Result<std::unique_ptr<SceneRenderer>> made =
            SceneRenderer::create(library_, setup.terrain);
        if (!made) {
            return made.error();
        }
        renderer_ = std::move(made.value());
    }
    return renderer_.get();
}

Scheduler& BatchRenderer::scheduler(const RenderSetup& setup) {
    if (!scheduler_) {
        // One worker per core; every batch image waits for all its levels
        // (RenderSettings::waitForTiles), so output does not depend on thread timing.
        SchedulerOptions schedulerOptions;
        schedulerOptions.format = TileFormat{setup.terrain.clipmapSize, 2};
        schedulerOptions.budgetBytes = setup.cacheMegabytes << 20;
        scheduler_ = std::make_unique<Scheduler>(schedulerOptions);
    }
    return *scheduler_;
}

Result<BatchSummary> BatchRenderer::run(BatchPlan& plan, BatchListener& listener,
                                        const std::atomic<bool>* cancel) {
    BatchRun run(plan, listener, cancel);
    const std::size_t tilesBefore = scheduler_ ? scheduler_->totals().misses : 0;
    if (Status rendered = renderImages(run); !rendered) {
        return rendered.error();
    }
    SeriesAssembler assembler(run);
    assembler.assemble();
    if (!run.cancelled()) {
        assembler.writeContactSheets();
    }
    BatchSummary summary = run.summary();
    if (scheduler_) {
        summary.tilesProduced = scheduler_->totals().misses - tilesBefore;
        summary.tilesCached = scheduler_->totals().tiles;
    }
    return summary;
}

Status BatchRenderer::renderImages(BatchRun& run) {
    for (const RenderJob& job : run.plan().jobs()) {
        if (job.kind != RenderJobKind::Image) {
            continue;
        }
        if (run.cancelled()) {
            return {};
        }
        if (run.skipIfCurrent(job)) {
            continue;
        }
        if (Status rendered = renderImage(run, job); !rendered) {
            return rendered;
        }
    }
    return {};
}

// One Image job: camera and sun, render, write, record. Only a renderer that cannot be
// made is an error here; the job's own failures are reported through the run.
Status BatchRenderer::renderImage(BatchRun& run, const RenderJob& job) {
    const auto start = std::chrono::steady_clock::now();
    const BatchPlan& plan = run.plan();
    const RenderSetup& setup = plan.setup();
    Scheduler& tiles = scheduler(setup);
    const std::size_t tilesBefore = tiles.totals().misses;
    // Each scenario renders its own model (overrides applied); unchanged sources keep
    // their content hashes, so their tiles come from the shared cache.
    const TerrainLayers& layers = plan.layersOf(job);
    Result<SceneRenderer*> renderer = sceneRenderer(setup);
    if (!renderer) {
        return renderer.error();
    }
    Result<JobView> view =
        JobView::forJob(plan.model(), job, layers, tiles, setup, plan.pathOf(job));
    if (!view) {
        run.fail(job, view.error().message);
        return {};
    }
    const std::string& what = view.value().what;
    const Camera& camera = view.value().camera;
    Result<bool> sheet = ViewpointOutput::wantsSheet(plan, job, camera);
    if (!sheet) {
        run.fail(job, sheet.error().message);
        return {};
    }
    Result<Image> image = PanoramaRenderer::render(*renderer.value(), layers, tiles, camera,
                                                   view.value().settingsFor(setup, job));
    if (!image) {
        run.fail(job, what + ": " + image.error().message);
        return {};
    }
    ImageMetadata metadata = plan.metadataFor(job);
    const std::optional<ViewpointRecord> record =
        ViewpointOutput::record(plan, job, camera, image.value().width, image.value().height);
    if (record) {
        record->addTo(metadata);
    }
    if (sheet.value()) {  // before the image, which moves its radiance out
        if (Status written = ViewpointOutput::writeSheet(plan, job, camera, image.value(), *record);
            !written) {
            run.fail(job, written.error().message);
            return {};
        }
    }
    if (Status written = ImageOutput::write(job.output, image.value(), metadata); !written) {
        run.fail(job, written.error().message);
        return {};
    }
    JobReport report;
    report.job = &job;
    report.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const RenderStatistics& stats = renderer.value()->statistics();
    report.tiles = tiles.totals().misses - tilesBefore;
    if (!stats.terrain.degraded.empty()) {
        // The image is written (coarser data is better than none), but the run must say
        // that data was missing.
        run.degrade(what + ": drawn with coarser terrain: " + stats.terrain.degraded);
    } else {
        run.record(job, start, report.tiles);
    }
    report.width = image.value().width;
    report.height = image.value().height;
    report.levels = stats.terrain.levels;
    report.triangles = stats.terrain.triangles;
    run.done(report);
    return {};
}

}  // namespace sylva::render
