// BatchPlan: the jobs of one batch run, decided before anything renders. From a
// project's scenarios (ScenarioGraphs) and its render setup it expands the view series
// (ViewSeries: every job with a stable index into the full list), selects the jobs of
// this run (views block, shard i/N, an index range, with or without comparisons, the
// images of one viewpoint for watching), orders them for the tile cache and computes
// what decides each job's pixels: the content hash of its scenario's layer sources,
// camera or path frame, settings and time (comparisons and videos combine the hashes of
// their inputs). That hash is the job's record in the manifest (RenderManifest), so
// `--resume` skips jobs whose record is current, and it goes into the images' metadata.
//
// CPU only, so a job listing or an analysis can use the same selection, hashes and
// manifest without GL. Errors are located (file:line:col) or name the path.
//
// Ownership: a plan points into the ScenarioGraphs it was made from (layers, models);
// it is valid while that object lives and is not replaced.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "sylva/core/base/Result.h"
#include "sylva/core/image/ImageMetadata.h"
#include "sylva/core/scene/CameraPath.h"
#include "sylva/core/scene/RenderManifest.h"
#include "sylva/core/scene/ViewSeries.h"
#include "sylva/core/sources/graph/ScenarioGraphs.h"
#include "sylva/render/batch/RenderSetup.h"

namespace sylva::render {

// Indices into the full job list, both included.
struct JobRange {
    std::size_t first = 0;
    std::size_t last = 0;
};

// Which jobs a run makes, where, and how it records them.
struct BatchSelection {
    std::filesystem::path outputFolder = "out";
    std::string views;                // one views block; every views block when empty
    std::pair<int, int> shard{1, 1};  // shard i of N (ViewSeries::shard)
    std::optional<JobRange> range;    // only jobs whose index lies in the range
    // A range reaching past the last job ends at it (render farms cut the series into
    // fixed-size chunks); a range starting past it is still an error.
    bool clampRange = false;
    // Compare/blend images and the videos made of them (and the contact sheets).
    bool comparisons = true;
    // Watching one viewpoint at a time: only Image jobs, only the first frame of each
    // path, only of this camera or path (when set).
    bool imagesOnly = false;
    bool firstFramesOnly = false;
    std::optional<std::string> viewpoint;
    // Skip jobs whose manifest record is current (and videos whose file is).
    bool resume = false;
    // Record finished jobs in OUTPUT/NAME.json (NAME.shard-i-of-N.json for a shard,
    // NAME.jobs-A-B.json for a range, so parallel processes never write one file); false:
    // no manifest at all. Reading (resume, isCurrent) also consults every other
    // OUTPUT/NAME*.json, so a run finds what other shards and ranges finished.
    bool manifest = true;
    std::string manifestName = "manifest";
};

class BatchPlan {
public:
    // Expands, selects and orders the jobs and computes their hashes (building the
    // scenario graphs they need). Errors: the series' located errors, a path that
    // cannot be sampled, a scenario that cannot be built, a range beyond the series.
    static Result<BatchPlan> make(ScenarioGraphs& project, const RenderSetup& setup,
                                  const BatchSelection& selection);

    // What must hold before the first image, without rendering anything: ffmpeg on PATH
    // when the plan writes videos (else a located error telling how to get it), every
    // output folder created and writable, and with `resume` the manifest read.
    Status prepareOutputs();
    // Reads the run's manifest, if there is one (a missing file is an empty manifest; a
    // corrupt one is an error naming it), so isCurrent() can answer; writes nothing.
    Status loadManifest();

    // Every job of the series, in ViewSeries order; job.index is the position here.
    const std::vector<RenderJob>& allJobs() const { return allJobs_; }
    // The jobs of this run in render order: the images of one viewpoint and scenario at
    // all their times one after another (times change only the sun, so later times find
    // their tiles cached), then comparisons and videos in series order.
    const std::vector<RenderJob>& jobs() const { return jobs_; }
    const RenderJob& job(std::size_t index) const { return allJobs_.at(index); }

    const BatchSelection& selection() const { return selection_; }
    const RenderSetup& setup() const { return setup_; }
    // The default scenario's model (cameras, paths, views, compare and blend blocks).
    const ProjectModel& model() const { return project_->defaultModel(); }

    // The hash of everything that decides the job's pixels (see above), for the jobs of
    // this run and the images and frames they are made of (SYLVA_CHECK otherwise).
    std::uint64_t hashOf(const RenderJob& job) const;
    // The layers of an Image job's scenario (same jobs as hashOf).
    const TerrainLayers& layersOf(const RenderJob& job) const;
    // The path a job samples (null for camera jobs).
    const CameraPath* pathOf(const RenderJob& job) const;
    // The comparison or blend block a Compare/Blend job is made by.
    const Block& comparisonBlock(const RenderJob& job) const;

    // The metadata every written file of `job` carries (view, camera or path and frame,
    // scenario or compared scenarios, time, project file and hashes, exposure, version).
    ImageMetadata metadataFor(const RenderJob& job) const;
    // The metadata of a views block's contact sheet.
    ImageMetadata sheetMetadata(const std::string& view) const;
    // The manifest record of `job` before it is made (no timing yet).
    ManifestEntry entryFor(const RenderJob& job) const;
    // With resume: whether the job, or the video it is a frame of, is recorded current
    // (in this run's manifest or another shard's or range's; the file exists).
    bool isCurrent(const RenderJob& job) const;
    // After loadManifest: Current (recorded with this hash, file present), Stale
    // (recorded with another hash, or the file is gone) or Missing (no record).
    enum class RecordState { Missing, Stale, Current };
    RecordState recordState(const RenderJob& job) const;
    // Records a finished job and saves the manifest atomically (a no-op without one).
    Status record(const ManifestEntry& entry);
    // `output` relative to the output folder ("today/beach_0900.png").
    std::string relativeOutput(const std::filesystem::path& output) const;
    // The manifest file of this run, or empty without one.
    std::filesystem::path manifestFile() const;

    // Whether this run makes the whole series (no shard, no range, no job left out), so
    // contact sheets show every image.
    bool wholeSeries() const;
    // ffmpeg's path once prepareOutputs() found it (empty when no video is planned).
    const std::string& ffmpeg() const { return ffmpeg_; }

    // "sylva:project_hash": every block of the project.
    std::uint64_t projectHash() const { return projectHash_; }
    // The project file as an absolute path (image metadata).
    const std::string& projectPath() const { return projectPath_; }

    // The kind as the manifest and progress name it: image, compare, blend, video.
    static std::string kindName(RenderJobKind kind);

private:
    BatchPlan() = default;
    Status select();
    void order();
    Status buildPaths();
    Status computeHash(std::size_t index);
    void computeProjectHash();

    ScenarioGraphs* project_ = nullptr;
    RenderSetup setup_;
    BatchSelection selection_;
    std::vector<RenderJob> allJobs_;
    std::vector<RenderJob> jobs_;
    std::map<std::size_t, std::uint64_t> hashes_;  // by job index
    std::map<std::size_t, TerrainLayers> layers_;  // by job index, Image jobs
    std::map<std::string, CameraPath> paths_;      // by path name
    std::optional<RenderManifest> manifest_;
    std::vector<RenderManifest> otherManifests_;  // other shards' and ranges' (read only)
    std::string ffmpeg_;
    std::uint64_t projectHash_ = 0;
    std::string projectPath_;
};

}  // namespace sylva::render
