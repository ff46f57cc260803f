// ViewSeries: expands the `views` blocks of a project into the list of images to make
// (issue "scenarios, comparison images, batch view series"): per views block, every
// camera and every frame of every path, × every scenario, × every time; then, per
// camera/frame and time, one comparison image for each `compare` and `blend` block
// whose two scenarios the series renders. Everything is decided before rendering:
// output paths from the template, collisions between jobs, bad times and paths are
// located errors.
//
// Output templates (relative to the output folder) replace {view}, {camera} (the
// camera, or the path for path frames), {path}, {frame} (5 digits), {scenario} (for
// comparison images: the compare/blend block's name), {time} (2024-06-21T0900-0300)
// and {time:FORMAT} with %Y %m %d %H %M %S %z of the time as written (its own zone).
// A series that contains comparisons must put {scenario} into its template. A blend
// with `steps = N` (N ≥ 2) is a sequence of N images at t = 0, 1/(N−1), … 1; its
// template needs {step} (000, 001, …) or {t} (0.000 … 1.000). Placeholders that do not
// apply to a job ({time} without times, {step} and {t} outside blend sequences,
// {frame} for cameras expands to 00000) vanish.
//
// A template ending in .mp4 makes one video per path (and scenario, time, comparison):
// its frames are rendered as PNGs into a hidden folder next to the video
// (".NAME.mp4.frames/00000.png"), then a Video job encodes them. Such a views block may
// only hold paths, and its template must not contain {frame}.
#pragma once

#include <cstddef>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "sylva/core/base/Result.h"
#include "sylva/core/model/ProjectModel.h"
#include "sylva/core/scene/DateTime.h"

namespace sylva {

enum class RenderJobKind { Image, Compare, Blend, Video };

struct RenderJob {
    RenderJobKind kind = RenderJobKind::Image;
    std::string view;      // views block name
    std::string camera;    // camera name (empty for path frames)
    std::string path;      // path name (empty for cameras)
    int frame = -1;        // path frame index, -1 for cameras
    double pathTime = 0;   // seconds into the path
    std::string scenario;  // scenario rendered (Image), or the compare/blend block name
    std::optional<DateTime> time;
    double unixSeconds = 0;        // the time as UTC instant, when `time` is set
    std::filesystem::path output;  // output folder / expanded template
    // Compare/Blend: indices (into the full job list) of the two images compared.
    std::size_t first = 0, second = 0;
    // Blend: the mix amount (the block's `amount`, or step / (steps − 1) of a sequence)
    // and the step of a sequence (-1 for a single blend image).
    double blendAmount = 0.5;
    int step = -1;
    // Video: the jobs of its frames in order, and the frame rate. Frames of a video
    // carry the index of their Video job.
    std::vector<std::size_t> frames;
    double framesPerSecond = 0;
    std::optional<std::size_t> video;
    bool videoFrame = false;  // a frame of a video (set before the group is chosen)
    std::size_t index = 0;    // position in the full list (shards keep it)
    std::size_t group = 0;    // viewpoint-and-time group, in order of first appearance
};

class ViewSeries {
public:
    // All jobs of `views` (all views blocks when empty) in a fixed order: images first,
    // then comparisons. Errors are located (file:line:col) and name the views block.
    static Result<std::vector<RenderJob>> expand(const ProjectModel& model,
                                                 const std::filesystem::path& outputFolder,
                                                 const std::string& views = {});
    // The template with the job's values filled in (see above).
    static Result<std::string> expandTemplate(const std::string& pattern, const RenderJob& job);
    // "i/N" (1 ≤ i ≤ N): shard i of N.
    static Result<std::pair<int, int>> parseShard(const std::string& text);
    // The jobs of shard `index` (1-based) of `count`: a deterministic partition where
    // every job is in exactly one shard. Jobs move by group — all scenarios and
    // comparisons of one view, camera/frame and time, so a comparison always lives with
    // the two images it is made of — and shard i takes the i-th contiguous block of
    // groups (in order of first appearance), so the times of one camera and consecutive
    // path frames, which share their tiles, mostly stay in one shard.
    static std::vector<RenderJob> shard(const std::vector<RenderJob>& jobs, int index, int count);
    // The group key used by shard(): equal for jobs that must stay together.
    static std::string groupOf(const RenderJob& job);
};

}  // namespace sylva
