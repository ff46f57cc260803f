#include "sylva/render/batch/BatchRun.h"

#include <algorithm>

namespace sylva::render {
namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

BatchRun::BatchRun(BatchPlan& plan, BatchListener& listener, const std::atomic<bool>* cancel)
    : plan_(plan), listener_(listener), cancel_(cancel), start_(std::chrono::steady_clock::now()) {
    summary_.total = plan.jobs().size();
}

bool BatchRun::cancelled() {
    if (cancel_ != nullptr && cancel_->load()) {
        summary_.cancelled = true;
    }
    return summary_.cancelled;
}

bool BatchRun::skipIfCurrent(const RenderJob& job) {
    if (!plan_.isCurrent(job)) {
        return false;
    }
    ++summary_.skipped;
    JobReport report;
    report.job = &job;
    report.skipped = true;
    done(report);
    return true;
}

void BatchRun::fail(const RenderJob& job, const std::string& message) {
    listener_.error(message);
    ++summary_.failed;
    failedJobs_.insert(job.index);
}

void BatchRun::failTransiently(const RenderJob& job, const std::string& message) {
    fail(job, message);
    ++summary_.transientFailures;
}

void BatchRun::degrade(const std::string& message) {
    listener_.error(message);
    ++summary_.degraded;
}

double BatchRun::record(const RenderJob& job, std::chrono::steady_clock::time_point start,
                        std::size_t tiles, int frames) {
    ManifestEntry entry = plan_.entryFor(job);
    entry.seconds = secondsSince(start);
    entry.tilesGenerated = tiles;
    if (frames >= 0) {
        entry.frame = frames;
    }
    if (Status saved = plan_.record(entry); !saved) {
        // The image is written but not recorded (a full disk, a shared filesystem that
        // failed): retrying with --resume redoes it, so the run stops as transient.
        failTransiently(job, saved.error().message);
    }
    return entry.seconds;
}

void BatchRun::done(JobReport report) {
    const std::size_t done = ++summary_.done;
    const std::size_t total = summary_.total;
    report.done = done;
    report.total = total;
    report.etaSeconds = secondsSince(start_) / static_cast<double>(done) *
                        static_cast<double>(total - std::min(done, total));
    listener_.jobDone(report);
}

}  // namespace sylva::render
