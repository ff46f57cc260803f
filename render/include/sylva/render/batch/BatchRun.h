// BatchRun: the bookkeeping of one run over a BatchPlan, shared by its phases (rendering
// images, assembling comparisons, videos and contact sheets): which jobs are done,
// skipped, failed or degraded, the manifest records, progress reports to the listener,
// and cancellation. CPU only.
//
// Cancellation: `cancel` (may be null) is read before every job; setting it (e.g. from a
// SIGINT handler: a lock-free atomic store is async-signal-safe) stops the run after the
// current job. Every file is written atomically and recorded only when complete, so a
// cancelled run leaves finished files and a manifest listing exactly those.
#pragma once

#include <atomic>
#include <chrono>
#include <cstddef>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "sylva/core/scene/RenderManifest.h"
#include "sylva/render/batch/BatchListener.h"
#include "sylva/render/batch/BatchPlan.h"

namespace sylva::render {

struct BatchSummary {
    std::size_t total = 0;   // jobs of the run
    std::size_t done = 0;    // written or skipped
    int skipped = 0;         // current by the manifest (resume)
    int failed = 0;          // not written
    int degraded = 0;        // written with coarser terrain than wanted (not recorded)
    bool cancelled = false;  // stopped by the cancel flag before every job was done
    // Failures worth retrying later (the output disk is full): the run stopped at the
    // first; finished files are recorded, so `--resume` continues (exit code 75).
    int transientFailures = 0;
    // Tiles the Scheduler produced during the run, and the tiles cached at its end.
    std::size_t tilesProduced = 0;
    std::size_t tilesCached = 0;
    std::size_t tilesFromDisk = 0;  // read from the disk tile cache instead of produced
};

class BatchRun {
public:
    BatchRun(BatchPlan& plan, BatchListener& listener, const std::atomic<bool>* cancel = nullptr);

    BatchPlan& plan() { return plan_; }
    BatchListener& listener() { return listener_; }

    // True once the cancel flag is set; the run marks itself cancelled.
    bool cancelled();
    // With resume, when `job` is current: reports it skipped and returns true.
    bool skipIfCurrent(const RenderJob& job);
    // The job could not be made: reports `message`, counts it.
    void fail(const RenderJob& job, const std::string& message);
    // A failure that another attempt may not have (the disk is full): counted in
    // `failed` and `transientFailures`; the image phase stops after it.
    void failTransiently(const RenderJob& job, const std::string& message);
    bool stoppedTransiently() const { return summary_.transientFailures > 0; }
    bool failed(std::size_t jobIndex) const { return failedJobs_.count(jobIndex) != 0; }
    // The image was written with missing data: reports `message`, counts it (the job
    // is not recorded, so --resume makes it again).
    void degrade(const std::string& message);
    // Records the finished job in the manifest (a save error is reported, the run goes
    // on) with the seconds since `start`, the tiles produced for it and, for a video,
    // its frame count. Returns those seconds.
    double record(const RenderJob& job, std::chrono::steady_clock::time_point start,
                  std::size_t tiles = 0, int frames = -1);
    // Reports the job done (progress: done, total, ETA are filled in here).
    void done(JobReport report);

    // The depth buffer of an image a wireline comparison needs (`compare { mode =
    // wireline }`): kept from the image phase to the assemble phase, in memory only
    // (reversed-Z as RenderedDepth: planar along the axis, a panorama along each ray).
    struct Depth {
        std::vector<float> depth;
        double near = 1.0;
    };
    void keepDepth(std::size_t jobIndex, Depth depth) { depths_[jobIndex] = std::move(depth); }
    // The kept depth of job `jobIndex`, or null.
    const Depth* depthOf(std::size_t jobIndex) const {
        const auto found = depths_.find(jobIndex);
        return found == depths_.end() ? nullptr : &found->second;
    }

    const BatchSummary& summary() const { return summary_; }
    BatchSummary& summary() { return summary_; }

private:
    BatchPlan& plan_;
    BatchListener& listener_;
    const std::atomic<bool>* cancel_;
    std::chrono::steady_clock::time_point start_;
    std::set<std::size_t> failedJobs_;
    std::map<std::size_t, Depth> depths_;
    BatchSummary summary_;
};

}  // namespace sylva::render
