#include "sylva/render/batch/BatchPlan.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <set>
#include <system_error>
#include <tuple>

#include "sylva/core/base/Hash.h"
#include "sylva/core/image/ImageWriter.h"
#include "sylva/render/batch/VideoEncoder.h"

namespace sylva::render {
namespace {

std::string hexText(std::uint64_t value) {
    char text[20];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(value));
    return text;
}

// The kind a job counts as for --no-comparisons: a video is of the kind of its frames.
RenderJobKind contentKind(const RenderJob& job, const std::vector<RenderJob>& all) {
    return job.kind == RenderJobKind::Video ? all[job.frames.front()].kind : job.kind;
}

// Checks that `folder` exists (creating it) and accepts files.
Status checkWritable(const std::filesystem::path& folder) {
    std::error_code error;
    std::filesystem::create_directories(folder, error);
    if (error) {
        return Error{"cannot create output folder '" + folder.string() + "': " + error.message()};
    }
    const std::filesystem::path probe =
        folder / (".sylva-write-test-" + std::to_string(::getpid()));
    {
        std::ofstream stream(probe);
        if (!stream) {
            return Error{"cannot write to output folder '" + folder.string() +
                         "': permission denied or read-only"};
        }
    }
    std::filesystem::remove(probe, error);
    return {};
}

}  // namespace

std::string BatchPlan::kindName(RenderJobKind kind) {
    switch (kind) {
        case RenderJobKind::Image:
            return "image";
        case RenderJobKind::Compare:
            return "compare";
        case RenderJobKind::Blend:
            return "blend";
        case RenderJobKind::Video:
            return "video";
    }
    return "image";
}

Result<BatchPlan> BatchPlan::make(ScenarioGraphs& project, const RenderSetup& setup,
                                  const BatchSelection& selection) {
    BatchPlan plan;
    plan.project_ = &project;
    plan.setup_ = setup;
    plan.selection_ = selection;
    Result<std::vector<RenderJob>> expanded =
        ViewSeries::expand(project.defaultModel(), selection.outputFolder, selection.views);
    if (!expanded) {
        return expanded.error();
    }
    plan.allJobs_ = std::move(expanded.value());
    if (Status selected = plan.select(); !selected) {
        return selected.error();
    }
    plan.order();
    if (Status paths = plan.buildPaths(); !paths) {
        return paths.error();
    }
    plan.computeProjectHash();
    for (const RenderJob& job : plan.jobs_) {
        if (Status hashed = plan.computeHash(job.index); !hashed) {
            return hashed.error();
        }
    }
    if (selection.manifest) {
        plan.manifest_.emplace(plan.manifestFile());
    }
    return plan;
}

Status BatchPlan::select() {
    const std::vector<RenderJob>& all = allJobs_;
    const auto [shardIndex, shardCount] = selection_.shard;
    jobs_ = shardCount > 1 ? ViewSeries::shard(all, shardIndex, shardCount) : all;
    if (std::optional<JobRange>& range = selection_.range) {
        if (selection_.clampRange && range->first <= range->last && range->first < all.size()) {
            range->last = std::min(range->last, all.size() - 1);
        }
        if (range->first > range->last || range->last >= all.size()) {
            return Error{"jobs " + std::to_string(range->first) + "-" +
                         std::to_string(range->last) + " are not within the series' jobs 0-" +
                         std::to_string(all.empty() ? 0 : all.size() - 1)};
        }
    }
    std::erase_if(jobs_, [&](const RenderJob& job) {
        const std::optional<JobRange>& range = selection_.range;
        if (range && (job.index < range->first || job.index > range->last)) {
            return true;
        }
        const RenderJobKind kind = contentKind(job, all);
        if (!selection_.comparisons &&
            (kind == RenderJobKind::Compare || kind == RenderJobKind::Blend)) {
            return true;
        }
        if (selection_.imagesOnly && job.kind != RenderJobKind::Image) {
            return true;
        }
        if (selection_.firstFramesOnly && job.frame > 0) {
            return true;
        }
        const std::optional<std::string>& viewpoint = selection_.viewpoint;
        return viewpoint && job.camera != *viewpoint && job.path != *viewpoint;
    });
    return {};
}

void BatchPlan::order() {
    // With scenarios alternating, a large scenario's tiles push the other's out of the
    // budget; the images of one viewpoint and scenario are therefore kept together.
    // Comparisons and videos keep their place after the images.
    std::map<std::string, std::size_t> firstSeen;
    auto rank = [&](const std::string& key, std::size_t index) {
        return firstSeen.emplace(key, index).first->second;
    };
    std::map<std::size_t, std::tuple<std::size_t, std::size_t, std::size_t>> order;
    for (const RenderJob& job : jobs_) {
        const std::string viewpoint =
            job.view + "\n" + job.camera + "\n" + job.path + "\n" + std::to_string(job.frame);
        order[job.index] =
            job.kind == RenderJobKind::Image
                ? std::make_tuple(rank(viewpoint, job.index),
                                  rank(viewpoint + "\n" + job.scenario, job.index), job.index)
                : std::make_tuple(allJobs_.size(), allJobs_.size(), job.index);
    }
    std::stable_sort(jobs_.begin(), jobs_.end(), [&](const RenderJob& a, const RenderJob& b) {
        return order.at(a.index) < order.at(b.index);
    });
}

Status BatchPlan::buildPaths() {
    // Paths are checked (keys, heights) before the first image.
    for (const RenderJob& job : jobs_) {
        if (!job.path.empty() && !paths_.count(job.path)) {
            Result<CameraPath> path = CameraPath::fromBlock(*model().findPath(job.path));
            if (!path) {
                return path.error();
            }
            paths_.emplace(job.path, std::move(path.value()));
        }
    }
    return {};
}

void BatchPlan::computeProjectHash() {
    const ProjectModel& model = this->model();
    ContentHash hash;
    hash.add(model.render.contentHash).add(model.project.contentHash);
    for (const std::vector<Block>* blocks :
         {&model.sources, &model.scenarios, &model.cameras, &model.views, &model.compares,
          &model.blends, &model.paths, &model.params}) {
        for (const Block& block : *blocks) {
            hash.add(block.name).add(block.contentHash);
        }
    }
    projectHash_ = hash.value();
    projectPath_ = std::filesystem::absolute(model.file).lexically_normal().string();
}

Status BatchPlan::computeHash(std::size_t index) {
    if (hashes_.count(index)) {
        return {};
    }
    const RenderJob& job = allJobs_.at(index);
    const ProjectModel& model = this->model();
    ContentHash hash;
    if (job.kind == RenderJobKind::Image) {
        // The sources of its scenario (their hashes cover parameters and the files they
        // read), camera or path frame, settings and time.
        Result<TerrainLayers> layers = project_->terrainLayers(job.scenario);
        if (!layers) {
            return layers.error();
        }
        const Block* cameraBlock = job.camera.empty() ? nullptr : model.findCamera(job.camera);
        const Block* pathBlock = job.path.empty() ? nullptr : model.findPath(job.path);
        // The scenario's render block: `override render { ... }` may change it.
        Result<ScenarioGraph> scenario = project_->scenario(job.scenario);
        if (!scenario) {
            return scenario.error();
        }
        hash.add(scenario.value().model->render.contentHash)
            .add(setup_.settings.width)
            .add(setup_.settings.height);
        for (const Source* layer :
             {layers.value().elevation, layers.value().color, layers.value().normals}) {
            hash.add(layer ? layer->contentHash() : 0ull);
        }
        hash.add(cameraBlock ? cameraBlock->contentHash : pathBlock->contentHash)
            .add(job.frame)
            .add(job.pathTime)
            .add(job.time ? job.time->text() : std::string());
        hash.add(ImageWriter::isExr(job.output));
        layers_.emplace(index, layers.value());
    } else if (job.kind == RenderJobKind::Video) {
        hash.add(std::string("video")).add(job.framesPerSecond);
        for (std::size_t frame : job.frames) {
            if (Status framed = computeHash(frame); !framed) {
                return framed;
            }
            hash.add(hashes_.at(frame));
        }
    } else {
        for (std::size_t input : {job.first, job.second}) {
            if (Status made = computeHash(input); !made) {
                return made;
            }
        }
        hash.add(hashes_.at(job.first))
            .add(hashes_.at(job.second))
            .add(kindName(job.kind))
            .add(job.scenario)
            .add(comparisonBlock(job).contentHash)
            .add(job.blendAmount);
    }
    hashes_[index] = hash.value();
    return {};
}

Status BatchPlan::prepareOutputs() {
    // MP4 outputs need ffmpeg: say so before rendering anything.
    for (const RenderJob& job : jobs_) {
        if (job.kind == RenderJobKind::Video && ffmpeg_.empty()) {
            ffmpeg_ = VideoEncoder::findOnPath("ffmpeg");
            if (ffmpeg_.empty()) {
                const Block* views = model().findViews(job.view);
                const Attribute* output = views ? views->find("output") : nullptr;
                return Error{(output ? output->location.toString() : model().file.string()) +
                             ": views '" + job.view + "': writing MP4 (" +
                             relativeOutput(job.output) +
                             ") needs ffmpeg on PATH; install it (apt install ffmpeg) or output "
                             "PNG frames (e.g. output = \"{path}/{frame}.png\")"};
            }
        }
    }
    std::set<std::filesystem::path> folders;
    for (const RenderJob& job : jobs_) {
        const std::filesystem::path folder =
            job.output.has_parent_path() ? job.output.parent_path() : ".";
        if (folders.insert(folder).second) {
            if (Status writable = checkWritable(folder); !writable) {
                return writable;
            }
        }
    }
    return selection_.resume ? loadManifest() : Status();
}

namespace {

// Whether `file` (the run's own manifest) is a shard's or range's, so the plain
// NAME.json of whole-series runs is one of the others to consult.
bool entryFileIsOther(const std::filesystem::path& file, const BatchSelection& selection) {
    return file.filename() != selection.manifestName + ".json";
}

}  // namespace

Status BatchPlan::loadManifest() {
    if (!manifest_) {
        return {};
    }
    if (Status loaded = manifest_->load(); !loaded) {
        return loaded;
    }
    // The other shards' and ranges' manifests of the same name in the same folder.
    otherManifests_.clear();
    std::error_code error;
    const std::string prefix = selection_.manifestName + ".";
    std::vector<std::filesystem::path> files;
    for (const auto& entry : std::filesystem::directory_iterator(selection_.outputFolder, error)) {
        const std::string name = entry.path().filename().string();
        if (entry.path() != manifest_->file() && name.starts_with(prefix) &&
            name.ends_with(".json") && name.size() > prefix.size() + 5) {
            files.push_back(entry.path());
        }
    }
    std::sort(files.begin(), files.end());
    if (entryFileIsOther(manifest_->file(), selection_)) {
        files.push_back(selection_.outputFolder / (selection_.manifestName + ".json"));
    }
    for (const std::filesystem::path& file : files) {
        RenderManifest other(file);
        if (Status loaded = other.load(); !loaded) {
            return loaded;
        }
        otherManifests_.push_back(std::move(other));
    }
    return {};
}

BatchPlan::RecordState BatchPlan::recordState(const RenderJob& job) const {
    if (!manifest_) {
        return RecordState::Missing;
    }
    const std::string output = relativeOutput(job.output);
    const std::uint64_t hash = hashOf(job);
    RecordState state = RecordState::Missing;
    const auto consult = [&](const RenderManifest& manifest) {
        if (manifest.isCurrent(output, hash)) {
            state = RecordState::Current;
        } else if (manifest.entries().count(output) != 0 && state == RecordState::Missing) {
            state = RecordState::Stale;
        }
    };
    consult(*manifest_);
    for (const RenderManifest& other : otherManifests_) {
        consult(other);
    }
    return state;
}

std::uint64_t BatchPlan::hashOf(const RenderJob& job) const {
    const auto found = hashes_.find(job.index);
    SYLVA_CHECK(found != hashes_.end());
    return found->second;
}

const TerrainLayers& BatchPlan::layersOf(const RenderJob& job) const {
    const auto found = layers_.find(job.index);
    SYLVA_CHECK(found != layers_.end());
    return found->second;
}

const CameraPath* BatchPlan::pathOf(const RenderJob& job) const {
    auto found = paths_.find(job.path);
    return found == paths_.end() ? nullptr : &found->second;
}

const Block& BatchPlan::comparisonBlock(const RenderJob& job) const {
    SYLVA_CHECK(job.kind == RenderJobKind::Compare || job.kind == RenderJobKind::Blend);
    const std::vector<Block>& blocks =
        job.kind == RenderJobKind::Compare ? model().compares : model().blends;
    const auto block = std::find_if(blocks.begin(), blocks.end(),
                                    [&](const Block& b) { return b.name == job.scenario; });
    SYLVA_CHECK(block != blocks.end());
    return *block;
}

ImageMetadata BatchPlan::metadataFor(const RenderJob& job) const {
    ImageMetadata metadata;
    metadata.set("sylva:view", job.view);
    if (job.path.empty()) {
        metadata.set("sylva:camera", job.camera);
    } else {
        metadata.set("sylva:path", job.path);
        if (job.kind != RenderJobKind::Video) {
            metadata.set("sylva:frame", std::to_string(job.frame));
        }
    }
    if (job.kind == RenderJobKind::Image) {
        metadata.set("sylva:scenario", job.scenario);
    } else {
        metadata.set("sylva:" + kindName(job.kind), job.scenario);
        metadata.set("sylva:scenario",
                     allJobs_[job.first].scenario + " | " + allJobs_[job.second].scenario);
        if (job.kind == RenderJobKind::Blend) {
            char amount[32];
            std::snprintf(amount, sizeof amount, "%.6g", job.blendAmount);
            metadata.set("sylva:blend_amount", amount);
        }
    }
    if (job.time) {
        metadata.set("sylva:time", job.time->text());
    }
    metadata.set("sylva:project", projectPath_);
    metadata.set("sylva:project_hash", hexText(projectHash_));
    metadata.set("sylva:image_hash", hexText(hashOf(job)));
    metadata.set("sylva:exposure", std::to_string(setup_.settings.exposure));
    metadata.set("sylva:version", SYLVA_VERSION);
    return metadata;
}

ImageMetadata BatchPlan::sheetMetadata(const std::string& view) const {
    ImageMetadata metadata;
    metadata.set("sylva:view", view);
    metadata.set("sylva:project", projectPath_);
    metadata.set("sylva:project_hash", hexText(projectHash_));
    metadata.set("sylva:version", SYLVA_VERSION);
    return metadata;
}

ManifestEntry BatchPlan::entryFor(const RenderJob& job) const {
    ManifestEntry entry;
    entry.output = relativeOutput(job.output);
    entry.kind = kindName(job.kind);
    entry.view = job.view;
    entry.camera = job.camera;
    entry.path = job.path;
    entry.frame = job.frame;
    entry.scenario = job.scenario;
    entry.time = job.time ? job.time->text() : "";
    entry.hash = hashOf(job);
    return entry;
}

bool BatchPlan::isCurrent(const RenderJob& job) const {
    if (!selection_.resume || !manifest_) {
        return false;
    }
    const auto currentAnywhere = [&](const std::string& output, std::uint64_t hash) {
        return manifest_->isCurrent(output, hash) ||
               std::any_of(
                   otherManifests_.begin(), otherManifests_.end(),
                   [&](const RenderManifest& other) { return other.isCurrent(output, hash); });
    };
    // A video whose file is current needs none of its frames.
    if (job.video) {
        const auto video = hashes_.find(*job.video);
        if (video != hashes_.end() &&
            currentAnywhere(relativeOutput(allJobs_[*job.video].output), video->second)) {
            return true;
        }
    }
    return currentAnywhere(relativeOutput(job.output), hashOf(job));
}

Status BatchPlan::record(const ManifestEntry& entry) {
    if (!manifest_) {
        return {};
    }
    manifest_->record(entry);
    return manifest_->save();
}

std::string BatchPlan::relativeOutput(const std::filesystem::path& output) const {
    return output.lexically_normal()
        .lexically_relative(selection_.outputFolder.lexically_normal())
        .generic_string();
}

std::filesystem::path BatchPlan::manifestFile() const {
    if (!selection_.manifest) {
        return {};
    }
    const auto [index, count] = selection_.shard;
    std::string name = selection_.manifestName;
    if (count > 1) {
        name += ".shard-" + std::to_string(index) + "-of-" + std::to_string(count);
    }
    if (selection_.range) {
        name += ".jobs-" + std::to_string(selection_.range->first) + "-" +
                std::to_string(selection_.range->last);
    }
    return selection_.outputFolder / (name + ".json");
}

bool BatchPlan::wholeSeries() const {
    return selection_.shard.second == 1 && !selection_.range && selection_.comparisons &&
           !selection_.imagesOnly && !selection_.firstFramesOnly && !selection_.viewpoint;
}

}  // namespace sylva::render
