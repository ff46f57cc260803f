#include "sylva/render/batch/BatchRenderer.h"

#include <sys/statvfs.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <set>
#include <utility>

#include "sylva/core/base/Check.h"
#include "sylva/render/batch/ImageOutput.h"
#include "sylva/render/batch/JobView.h"
#include "sylva/render/batch/SeriesAssembler.h"
#include "sylva/render/batch/ViewpointOutput.h"
#include "sylva/render/scene/PanoramaRenderer.h"

namespace sylva::render {
namespace {

// Whether a failed write of `bytes` into `output`'s folder failed for want of space: the
// reason says so, or the filesystem has less room than the image uncompressed (the
// writer removed its partial file, so the space it took is free again).
bool outOfSpace(const std::filesystem::path& output, std::size_t bytes, const std::string& reason) {
    if (reason.find(std::strerror(ENOSPC)) != std::string::npos ||
        reason.find(std::strerror(EDQUOT)) != std::string::npos) {
        return true;
    }
    struct statvfs filesystem {};
    const std::filesystem::path folder = output.has_parent_path() ? output.parent_path() : ".";
    return ::statvfs(folder.c_str(), &filesystem) == 0 &&
           static_cast<std::uint64_t>(filesystem.f_bavail) * filesystem.f_frsize < bytes;
}

// The image jobs whose depth buffers a wireline comparison of the run needs.
std::set<std::size_t> depthsWanted(const BatchPlan& plan) {
    std::set<std::size_t> wanted;
    for (const RenderJob& job : plan.jobs()) {
        if (job.kind == RenderJobKind::Compare && SeriesAssembler::isWireline(plan, job)) {
            wanted.insert(job.first);
            wanted.insert(job.second);
        }
    }
    return wanted;
}

}  // namespace

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
    if (renderer_) {
        renderer_->finishAssetBuilds();  // they read plant models of the graphs going now
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
    if (!setup) {
        return setup;
    }
    if (options_.cacheMegabytes) {
        setup->cacheMegabytes = *options_.cacheMegabytes;
    }
    if (options_.diskCacheMegabytes) {
        setup->diskCacheMegabytes = *options_.diskCacheMegabytes;
    }
    if (options_.diskCacheDisabled) {
        setup->diskCacheFolder.reset();
    } else if (options_.diskCacheFolder) {
        setup->diskCacheFolder = options_.diskCacheFolder;
    } else if (!setup->diskCacheFolder && options_.diskCacheByDefault) {
        setup->diskCacheFolder = DiskTileCache::defaultFolder();
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
    contextOptions.visible = options_.visibleWindow;
    contextOptions.title = options_.windowTitle;
    if (options_.width > 0 && options_.height > 0) {
        contextOptions.width = options_.width;
        contextOptions.height = options_.height;
    }
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
        if (setup.diskCacheFolder) {
            DiskTileCacheOptions disk;
            disk.folder = *setup.diskCacheFolder;
            disk.budgetBytes = setup.diskCacheMegabytes << 20;
            disk.warningSink = options_.warningSink;
            schedulerOptions.diskCache = std::make_shared<DiskTileCache>(std::move(disk));
        }
        schedulerOptions.taskSink = options_.schedulerTaskSink;
        scheduler_ = std::make_unique<Scheduler>(schedulerOptions);
    }
    return *scheduler_;
}

Result<BatchSummary> BatchRenderer::run(BatchPlan& plan, BatchListener& listener,
                                        const std::atomic<bool>* cancel) {
    BatchRun run(plan, listener, cancel);
    const std::size_t tilesBefore = scheduler_ ? scheduler_->totals().misses : 0;
    const std::size_t diskBefore = scheduler_ ? scheduler_->totals().diskHits : 0;
    if (Status rendered = renderImages(run); !rendered) {
        return rendered.error();
    }
    SeriesAssembler assembler(run);
    if (!run.stoppedTransiently()) {
        assembler.assemble();
    }
    if (!run.cancelled() && !run.stoppedTransiently()) {
        assembler.writeContactSheets();
    }
    BatchSummary summary = run.summary();
    if (scheduler_) {
        summary.tilesProduced = scheduler_->totals().misses - tilesBefore;
        summary.tilesCached = scheduler_->totals().tiles;
        summary.tilesFromDisk = scheduler_->totals().diskHits - diskBefore;
    }
    return summary;
}

Status BatchRenderer::renderImages(BatchRun& run) {
    // A wireline's depth buffers live in memory only: its images are rendered again on
    // --resume even when current.
    const std::set<std::size_t> depths = depthsWanted(run.plan());
    for (const RenderJob& job : run.plan().jobs()) {
        if (job.kind != RenderJobKind::Image) {
            continue;
        }
        if (run.cancelled() || run.stoppedTransiently()) {
            return {};
        }
        const bool keepDepth = depths.count(job.index) != 0;
        if (!keepDepth && run.skipIfCurrent(job)) {
            continue;
        }
        if (Status rendered = renderImage(run, job, keepDepth); !rendered) {
            return rendered;
        }
    }
    return {};
}

// One Image job: camera and sun, render, write, record. Only a renderer that cannot be
// made is an error here; the job's own failures are reported through the run.
Status BatchRenderer::renderImage(BatchRun& run, const RenderJob& job, bool keepDepth) {
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
    // The scenario's own render block (`override render { ... }`): its settings, at the
    // plan's image size; tile cache and clipmap levels stay the plan's.
    Result<ScenarioGraph> scenario = project().scenario(job.scenario);
    Result<RenderSetup> scenarioSetup =
        scenario ? RenderSetup::fromModel(*scenario.value().model, setup.settings.width,
                                          setup.settings.height)
                 : Result<RenderSetup>(scenario.error());
    if (!scenarioSetup) {
        run.fail(job, scenarioSetup.error().message);
        return {};
    }
    Result<JobView> view =
        JobView::forJob(plan.model(), job, layers, tiles, scenarioSetup.value(), plan.pathOf(job));
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
    RenderedDepth depth;
    Result<Image> image = PanoramaRenderer::render(
        *renderer.value(), layers, tiles, camera,
        view.value().settingsFor(scenarioSetup.value(), job), keepDepth ? &depth : nullptr);
    if (!image) {
        run.fail(job, what + ": " + image.error().message);
        return {};
    }
    if (keepDepth) {  // planar or cylindrical (ViewSeries makes no equirectangular wireline)
        run.keepDepth(job.index, {std::move(depth.depth), depth.near});
    }
    ImageMetadata metadata = plan.metadataFor(job);
    const std::optional<ViewpointRecord> record = ViewpointOutput::record(
        plan, job, camera, image.value().width, image.value().height, tiles);
    if (record) {
        record->addTo(metadata);
    }
    if (Status written = ImageOutput::write(job.output, image.value(), metadata); !written) {
        const std::size_t bytes = static_cast<std::size_t>(image.value().width) *
                                      static_cast<std::size_t>(image.value().height) * 8 +
                                  (64u << 10);
        if (outOfSpace(job.output, bytes, written.error().message)) {
            run.failTransiently(job, written.error().message + " (the disk is full)");
        } else {
            run.fail(job, written.error().message);
        }
        return {};
    }
    // The sheet only after its image is written (the sheet shows that file; the image
    // write moved only the radiance out, the sheet reads the 8-bit pixels). A sheet that
    // fails takes its image with it: the job failed, nothing half-written is left.
    if (sheet.value()) {
        if (Status written = ViewpointOutput::writeSheet(plan, job, camera, image.value(), *record);
            !written) {
            std::error_code ignored;
            std::filesystem::remove(job.output, ignored);
            run.fail(job, written.error().message);
            return {};
        }
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
