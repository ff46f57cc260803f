#include "sylva/bench/ViewerBenchmark.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "sylva/core/scene/FrameHoles.h"
#include "sylva/core/scene/ViewerScript.h"
#include "sylva/dsl/ProjectLoader.h"
#include "sylva/render/batch/BatchRenderer.h"
#include "sylva/render/viewer/Viewer.h"

namespace sylva::bench {
namespace {

// Reloading is not part of the benchmark; cameras are not saved.
class BenchmarkHost final : public render::ViewerHost {
public:
    explicit BenchmarkHost(std::filesystem::path project) : project_(std::move(project)) {}
    Result<std::vector<ProjectModel>> loadProject() override {
        dsl::LoadResult loaded = dsl::loadProject(project_);
        files_ = loaded.files;
        if (loaded.hasErrors() || !loaded.model) {
            return Error{loaded.render()};
        }
        return loaded.scenarios.empty() ? std::vector<ProjectModel>{std::move(*loaded.model)}
                                        : std::move(loaded.scenarios);
    }
    std::vector<std::filesystem::path> projectFiles() const override { return files_; }
    Status saveCamera(const std::string&, const Camera&, const std::string&) override {
        return Error{"the viewer benchmark saves no cameras"};
    }

private:
    std::filesystem::path project_;
    std::vector<std::filesystem::path> files_;
};

struct FrameRecord {
    double end = 0;  // seconds since the start
    double milliseconds = 0;
    bool pending = false;
    bool moved = false;
    int level = 0;
    bool refined = false;  // a still view's full-detail refinement, outside the budget
    bool holes = false;
    double startupSeconds = 0;  // the viewer's preparation before its first frame
};

std::string flightScript(const ViewerBenchmarkOptions& options) {
    std::string script = "camera space\nframes 4\ncamera aircraft\nframes 4\n";
    for (int i = 0; i < options.flightSteps; ++i) {
        script += "fly 300 0 -150\nframes 1\n";  // towards and down to the forest
    }
    script += "camera ground\nmode walk\n";
    for (int i = 0; i < options.flightSteps; ++i) {
        script += "fly 1.5 0 0\nframes 1\n";
    }
    // Still: the frames asked for, then on until nothing is pending; then one more frame,
    // the still view's refinement at full detail, and on until its own tiles came.
    script +=
        "frames " + std::to_string(options.stillFrames) + "\nwait-tiles\nframes 1\nwait-tiles\n";
    return script;
}

double percentile(std::vector<double> values, double p) {
    if (values.empty()) {
        return 0;
    }
    std::sort(values.begin(), values.end());
    const std::size_t index =
        std::min(values.size() - 1, static_cast<std::size_t>(std::ceil(p * values.size())) - 1);
    return values[index];
}

MetricList metricsOf(const std::vector<FrameRecord>& frames, double budget) {
    // Frame times of the frames the budget governs: a still view's refinement frames are
    // full detail by design (they end in seconds_to_full_detail_after_stop), and the
    // script's still `frames N` redraws a refined view N times where the window would idle.
    std::vector<double> milliseconds;
    std::size_t refined = 0;
    std::size_t holes = 0;
    std::size_t lastMoving = 0;
    for (std::size_t i = 0; i < frames.size(); ++i) {
        refined += frames[i].refined ? 1 : 0;
        if (!frames[i].refined) {
            milliseconds.push_back(frames[i].milliseconds);
        }
        holes += frames[i].holes ? 1 : 0;
        if (frames[i].moved) {
            lastMoving = i;
        }
    }
    // Still frames: after the last moving one. Full detail: the first at full detail (a
    // refinement, or level 0) with nothing pending from which the level stays as it ends.
    const std::size_t first = lastMoving + 1;
    const double stop = frames.empty() ? 0 : frames[lastMoving].end;
    double toFull = -1;
    for (std::size_t i = first; i < frames.size(); ++i) {
        bool settled = !frames[i].pending && (frames[i].refined || frames[i].level == 0);
        for (std::size_t j = i; j < frames.size() && settled; ++j) {
            settled = frames[j].level == frames.back().level;
        }
        if (settled) {
            toFull = frames[i].end - stop;
            break;
        }
    }
    std::size_t reversals = 0;
    int lastDirection = 0;
    for (std::size_t i = first + 1; i < frames.size(); ++i) {
        const int change = frames[i].level - frames[i - 1].level;
        const int direction = change > 0 ? 1 : change < 0 ? -1 : 0;
        if (direction != 0) {
            reversals += (lastDirection != 0 && direction != lastDirection) ? 1 : 0;
            lastDirection = direction;
        }
    }
    const double stillSeconds =
        frames.empty() || first >= frames.size() ? 0 : frames.back().end - frames[lastMoving].end;
    const double p95 = percentile(milliseconds, 0.95);
    return {{"frame_ms_p50", percentile(milliseconds, 0.5)},
            {"frame_ms_p95", p95},
            {"budget_overrun_p95", budget > 0 ? p95 / budget : 0},
            {"frames_with_holes", double(holes)},
            {"seconds_to_full_detail_after_stop", toFull},
            {"quality_oscillations", stillSeconds > 0 ? reversals / stillSeconds : 0},
            // Outside the frames, so reported: the preparation (plant species, a first
            // frame at the coarsest level) before the first interactive frame.
            {"startup_seconds", frames.empty() ? 0.0 : frames.front().startupSeconds},
            {"budgeted_frames", double(milliseconds.size())},
            {"refined_frames", double(refined)}};
}

// One line for a Scheduler task: where its worker's time went (inputs it produced itself
// hold the worker as long as the task; while every worker is in one the queue stands).
void traceTask(std::FILE* trace, const char* what, const SchedulerTaskReport& task) {
    std::string nested;
    for (const auto& [name, count] : task.producedPerSource) {
        nested += (nested.empty() ? "" : ", ") + name + " " + std::to_string(count);
    }
    std::fprintf(trace,
                 "  %s worker %d: %s %s%s, started t %.2f s, %.2f s, waited %.2f s, inputs "
                 "produced %zu (%s), read from disk %zu\n",
                 what, task.worker, task.source.c_str(), task.key.toString().c_str(),
                 task.fromDisk ? " (from disk)" : "", task.startSeconds, task.seconds,
                 task.waitSeconds, task.produced, nested.c_str(), task.diskReads);
}

// Tasks shorter than this are not traced (most are milliseconds).
constexpr double kTracedTaskSeconds = 0.5;

}  // namespace

std::string ViewerBenchmarkResult::json() const {
    return metricsJson("viewer", metrics, {NumberFormat::Notation::Fixed, 3});
}

Result<ViewerBenchmarkResult> runViewerBenchmark(const ViewerBenchmarkOptions& options) {
    BenchmarkHost host(options.project);
    Result<std::vector<ProjectModel>> models = host.loadProject();
    if (!models) {
        return Error{options.project.string() + ": " + models.error().message +
                     " (the Olinda data: run scripts/fetch-samples)"};
    }
    render::BatchOptions batchOptions;
    batchOptions.width = options.width;
    batchOptions.height = options.height;
    batchOptions.diskCacheFolder = options.diskCache;
    batchOptions.diskCacheDisabled = !options.diskCache;
    if (options.trace != nullptr) {
        batchOptions.schedulerTaskSink = [trace = options.trace](const SchedulerTaskReport& task) {
            if (task.seconds >= kTracedTaskSeconds) {
                traceTask(trace, "task", task);
            }
        };
    }
    render::BatchRenderer batch(batchOptions);
    if (Status set = batch.setProject(std::move(models.value())); !set) {
        return set.error();
    }
    Result<std::vector<ScriptCommand>> script =
        ViewerScript::parse(flightScript(options), "viewer-benchmark.script", ".");
    if (!script) {
        return script.error();
    }
    const auto start = std::chrono::steady_clock::now();
    std::vector<FrameRecord> frames;
    render::ViewerOptions viewerOptions;
    viewerOptions.budgetMilliseconds = options.budgetMilliseconds;
    viewerOptions.script = std::move(script.value());
    viewerOptions.closeAfterScript = true;
    viewerOptions.log = stderr;
    viewerOptions.onFrame = [&](const render::ViewerFrame& frame) {
        FrameRecord record;
        record.end =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        record.milliseconds = frame.milliseconds;
        record.pending = frame.pending;
        record.moved = frame.moved;
        record.level = frame.budgetLevel;
        record.refined = frame.refined;
        record.startupSeconds = frame.startupSeconds;
        // Holes beyond twice the near plane (FrameHoles): nearer, a ray under the
        // ellipsoid may pass under the camera's own ground legitimately.
        const FrameHoles holes = FrameHoles::count(*frame.camera, *frame.depth, frame.width,
                                                   frame.height, 2.0 * frame.near);
        record.holes = holes.holes > 0;
        frames.push_back(record);
        if (options.trace != nullptr) {
            std::fprintf(options.trace,
                         "frame %zu: t %.2f s, %.1f ms, %s%s%s, budget level %d, terrain levels "
                         "%d/%d, holes %d (first at %d,%d)\n",
                         frames.size() - 1, record.end, record.milliseconds,
                         record.moved ? "moved" : "still", record.pending ? ", pending" : "",
                         record.refined ? ", refined" : "", record.level, frame.levelsDrawn,
                         frame.levelsWanted, holes.holes, holes.firstX, holes.firstY);
            if (frame.statistics != nullptr) {
                // Why the frame is pending, and where its time went.
                const render::RenderStatistics& s = *frame.statistics;
                std::fprintf(options.trace,
                             "  height %.2f m, ground %.2f m (level %d), terrain waiting %d, "
                             "wanted %d..%d, canopy waiting %d, instance tiles %zu/%zu, "
                             "species pending %zu, queued %zu; update %.1f ms, terrain %.1f ms, "
                             "vegetation %.1f ms, canopy %.1f ms, shadows %.1f ms, ssao %.1f ms, "
                             "uploaded %.2f MB\n",
                             frame.camera->geodetic.height, s.groundHeight, s.groundLevel,
                             s.terrain.waitingLevel, s.terrain.wanted.coarsest,
                             s.terrain.wanted.finest, s.farField.waiting ? 1 : 0,
                             s.vegetationStream.readyTiles, s.vegetationStream.wantedTiles,
                             s.pendingSpecies, frame.queuedTiles, s.terrain.updateSeconds * 1e3,
                             s.terrainPassSeconds * 1e3, s.vegetationPassSeconds * 1e3,
                             s.farFieldPassSeconds * 1e3, s.shadowPassSeconds * 1e3,
                             s.ambientOcclusionPassSeconds * 1e3,
                             double(s.terrain.uploadedBytes) / (1 << 20));
                // The level the ground near the camera is drawn from, and whether it was
                // capped under a camera below every resident level's ground.
                char ceiling[32] = "none";
                if (s.terrain.nadirCeiling) {
                    std::snprintf(ceiling, sizeof ceiling, "%.2f m", *s.terrain.nadirCeiling);
                }
                std::fprintf(
                    options.trace,
                    "  texture level %d, resident level %d, nadir ceiling %s, near %.3f m\n",
                    s.terrain.textureLevel, s.terrain.residentLevel, ceiling, frame.near);
            }
            if (Result<render::RenderSetup> setup = batch.setup(); setup) {
                // What holds the workers now (a queue that stands: both in long tasks?).
                for (const SchedulerTaskReport& task :
                     batch.scheduler(setup.value()).runningTasks()) {
                    if (task.seconds >= kTracedTaskSeconds) {
                        traceTask(options.trace, "running", task);
                    }
                }
            }
            std::fflush(options.trace);
        }
    };
    render::Viewer viewer(batch, host, std::move(viewerOptions));
    if (Status ran = viewer.run(); !ran) {
        return ran.error();
    }
    if (Result<render::RenderSetup> setup = batch.setup(); options.trace != nullptr && setup) {
        // Where the workers' time went (tiles produced per source, seconds of produce()).
        for (const SchedulerStatistics& source :
             batch.scheduler(setup.value()).statisticsPerSource()) {
            std::fprintf(options.trace,
                         "source %s: %zu produced, %zu from disk, %zu hits, %.1f s producing\n",
                         source.name.c_str(), source.misses, source.diskHits, source.hits,
                         source.produceSeconds);
        }
    }
    ViewerBenchmarkResult result;
    result.metrics = metricsOf(frames, options.budgetMilliseconds);
    return result;
}

}  // namespace sylva::bench
