#include "sylva/core/scene/ViewSeries.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <map>

#include "sylva/core/model/BlockReader.h"
#include "sylva/core/scene/CameraPath.h"

namespace sylva {
namespace {

// Fields of a canonical DateTime text "YYYY-MM-DDThh:mm:ss±hh:mm".
struct TimeFields {
    std::string year, month, day, hour, minute, second, zone;
};

TimeFields fieldsOf(const DateTime& time) {
    const std::string text = time.text();
    TimeFields fields;
    fields.year = text.substr(0, 4);
    fields.month = text.substr(5, 2);
    fields.day = text.substr(8, 2);
    fields.hour = text.substr(11, 2);
    fields.minute = text.substr(14, 2);
    fields.second = text.substr(17, 2);
    const std::string zone = text.substr(19);
    fields.zone = zone.size() == 6 ? zone.substr(0, 3) + zone.substr(4, 2) : "";
    return fields;
}

std::string locationOf(const Block& block, std::string_view attribute) {
    if (const Attribute* found = block.find(attribute)) {
        return found->location.toString();
    }
    return block.location.toString();
}

bool endsWithMp4(const std::string& pattern) {
    if (pattern.size() < 4) {
        return false;
    }
    std::string extension = pattern.substr(pattern.size() - 4);
    for (char& c : extension) {
        c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    }
    return extension == ".mp4";
}

// Where frame `frame` of the video `video` is rendered before encoding.
std::filesystem::path framePath(const std::filesystem::path& video, int frame) {
    char name[32];
    std::snprintf(name, sizeof name, "%05d.png", std::max(frame, 0));
    std::string folder = video.filename().string();
    folder.insert(folder.begin(), '.');  // (built in place: GCC 12 warns on "." + string)
    folder.append(".frames");
    return video.parent_path() / folder / name;
}

// A viewpoint of a series: a camera, or one frame of a path.
struct Viewpoint {
    std::string camera, path;
    int frame = -1;
    double pathTime = 0;
};

// One views block being expanded: its output template and whether that makes videos.
struct Series {
    const Block* views = nullptr;
    std::string pattern;
    bool video = false;
};

// The video file a job is a frame of (empty: none) and the views block that makes it.
using VideoOf = std::pair<std::filesystem::path, const Block*>;

// An MP4 template holds whole paths: no cameras, no {frame}.
Status checkVideoSeries(const Series& series, const BlockReader& reader) {
    const Block& views = *series.views;
    if (series.video && !reader.references("cameras").empty()) {
        return Error{locationOf(views, "output") + ": views '" + views.name +
                     "': an MP4 output holds the frames of paths; render cameras in another "
                     "views block with an image template such as \"{camera}.png\""};
    }
    if (series.video && series.pattern.find("{frame}") != std::string::npos) {
        return Error{locationOf(views, "output") + ": views '" + views.name +
                     "': an MP4 holds every frame of a path; remove {frame} from the output "
                     "template"};
    }
    return {};
}

// The `times` of a views block (one empty time without them); every entry needs a date,
// a time of day and a zone.
Result<std::vector<std::optional<DateTime>>> timesOf(const Block& views) {
    std::vector<std::optional<DateTime>> times;
    if (const Attribute* written = views.find("times")) {
        if (const ValueList* list = written->value.get<ValueList>()) {
            for (const Value& item : *list) {
                const std::string* text = item.get<std::string>();
                Result<DateTime> parsed =
                    text ? DateTime::parse(*text) : Result<DateTime>(Error{"not a time"});
                if (!parsed) {
                    return Error{item.location.toString() + ": views '" + views.name +
                                 "': " + parsed.error().message};
                }
                if (Result<double> instant = parsed.value().unixSeconds(); !instant) {
                    return Error{item.location.toString() + ": views '" + views.name +
                                 "': " + instant.error().message};
                }
                times.push_back(parsed.value());
            }
        }
    }
    if (times.empty()) {
        times.push_back(std::nullopt);
    }
    return times;
}

// Cameras, then every frame of every path.
Result<std::vector<Viewpoint>> viewpointsOf(const ProjectModel& model, const BlockReader& reader) {
    std::vector<Viewpoint> viewpoints;
    for (const std::string& camera : reader.references("cameras")) {
        if (!model.findCamera(camera)) {
            return Error{reader.where("cameras") + "unknown camera '" + camera + "'"};
        }
        viewpoints.push_back({camera, "", -1, 0});
    }
    for (const std::string& pathName : reader.references("paths")) {
        const Block* pathBlock = model.findPath(pathName);
        if (!pathBlock) {
            return Error{reader.where("paths") + "unknown path '" + pathName + "'"};
        }
        Result<CameraPath> path = CameraPath::fromBlock(*pathBlock);
        if (!path) {
            return path.error();
        }
        for (int frame = 0; frame < path.value().frameCount(); ++frame) {
            viewpoints.push_back({"", pathName, frame, path.value().frameTime(frame)});
        }
    }
    if (viewpoints.empty()) {
        return Error{reader.where() + "no cameras or paths to render"};
    }
    return viewpoints;
}

// The jobs of the views blocks of one expand(), in order: per block, viewpoint and time
// the images of every scenario, then the comparisons made of them; finish() appends
// one Video job per video and checks that no two jobs write one file.
class SeriesExpansion {
public:
    SeriesExpansion(const ProjectModel& model, const std::filesystem::path& outputFolder)
        : model_(model), outputFolder_(outputFolder) {}

    Status add(const Block& views);
    Result<std::vector<RenderJob>> finish();

private:
    Status addImages(const Series& series, const Viewpoint& viewpoint,
                     const std::optional<DateTime>& time,
                     const std::vector<std::string>& scenarios);
    // The compare (or blend) images whose two scenarios are among the images from
    // `firstImage` on.
    Status addComparisons(const Series& series, std::size_t firstImage,
                          const std::vector<Block>& blocks, RenderJobKind kind,
                          const char* firstName, const char* secondName);
    // Whether comparison `block` is made for the viewpoint of `image` (wirelines: planar).
    bool wirelineApplies(const Block& block, const RenderJob& image) const;
    // The number of images of a blend (`steps`, 1 without); sets its amount.
    Result<int> blendSteps(const Series& series, const Block& block, RenderJob& job) const;
    // Where a job goes: its file, or for videos a frame in the video's frames folder.
    VideoOf place(const Series& series, RenderJob& job, const std::string& name) const;
    Status addVideos(std::vector<RenderJob>& jobs, const std::vector<VideoOf>& videoFiles) const;
    // Two jobs onto one file: the template lacks a placeholder that tells them apart.
    Status checkOutputs(std::vector<RenderJob>& jobs) const;

    const ProjectModel& model_;
    const std::filesystem::path& outputFolder_;
    std::vector<RenderJob> images_;
    std::vector<RenderJob> comparisons_;
    std::map<std::string, std::size_t> groups_;
    std::vector<VideoOf> imageVideos_, comparisonVideos_;  // per image / comparison
};

Status SeriesExpansion::add(const Block& views) {
    BlockReader reader(views, SchemaRegistry::builtin().find("views"));
    Series series;
    series.views = &views;
    series.pattern = reader.string("output", "{camera}.png");
    series.video = endsWithMp4(series.pattern);
    if (Status valid = checkVideoSeries(series, reader); !valid) {
        return valid;
    }
    std::vector<std::string> scenarios = reader.references("scenarios");
    if (scenarios.empty()) {
        scenarios.push_back(model_.scenarios.empty() ? std::string()
                                                     : model_.scenarios.front().name);
    }
    Result<std::vector<std::optional<DateTime>>> times = timesOf(views);
    if (!times) {
        return times.error();
    }
    Result<std::vector<Viewpoint>> viewpoints = viewpointsOf(model_, reader);
    if (!viewpoints) {
        return viewpoints.error();
    }
    for (const Viewpoint& viewpoint : viewpoints.value()) {
        for (const std::optional<DateTime>& time : times.value()) {
            const std::size_t firstImage = images_.size();
            if (Status added = addImages(series, viewpoint, time, scenarios); !added) {
                return added;
            }
            if (Status added = addComparisons(series, firstImage, model_.compares,
                                              RenderJobKind::Compare, "left", "right");
                !added) {
                return added;
            }
            if (Status added = addComparisons(series, firstImage, model_.blends,
                                              RenderJobKind::Blend, "from", "to");
                !added) {
                return added;
            }
        }
    }
    return {};
}

Status SeriesExpansion::addImages(const Series& series, const Viewpoint& viewpoint,
                                  const std::optional<DateTime>& time,
                                  const std::vector<std::string>& scenarios) {
    for (const std::string& scenario : scenarios) {
        RenderJob job;
        job.view = series.views->name;
        job.camera = viewpoint.camera;
        job.path = viewpoint.path;
        job.frame = viewpoint.frame;
        job.pathTime = viewpoint.pathTime;
        job.scenario = scenario;
        job.time = time;
        job.unixSeconds = time ? time->unixSeconds().value() : 0.0;
        Result<std::string> name = ViewSeries::expandTemplate(series.pattern, job);
        if (!name) {
            return Error{locationOf(*series.views, "output") + ": views '" + series.views->name +
                         "': " + name.error().message};
        }
        job.videoFrame = series.video;
        imageVideos_.push_back(place(series, job, name.value()));
        const std::string key = ViewSeries::groupOf(job);
        job.group = groups_.emplace(key, groups_.size()).first->second;
        images_.push_back(std::move(job));
    }
    return {};
}

// A wireline comparison needs the depth buffer of one render per scenario: planar, or a
// cylindrical panorama's resampled from its strips (PanoramaFaces::resampleDepth); an
// equirectangular image gets no wireline (not tested: its poles' cube faces).
bool SeriesExpansion::wirelineApplies(const Block& block, const RenderJob& image) const {
    const Value* mode = BlockReader(block, nullptr).value("mode");
    if (mode == nullptr || mode->get<Word>() == nullptr || mode->get<Word>()->text != "wireline" ||
        image.camera.empty()) {
        return true;
    }
    const Block* camera = model_.findCamera(image.camera);
    const Value* projection =
        camera != nullptr ? BlockReader(*camera, nullptr).value("projection") : nullptr;
    return projection == nullptr || projection->get<Word>() == nullptr ||
           projection->get<Word>()->text == "planar" ||
           projection->get<Word>()->text == "cylindrical";
}

Status SeriesExpansion::addComparisons(const Series& series, std::size_t firstImage,
                                       const std::vector<Block>& blocks, RenderJobKind kind,
                                       const char* firstName, const char* secondName) {
    auto imageOf = [&](const std::string& scenario) -> std::optional<std::size_t> {
        for (std::size_t i = firstImage; i < images_.size(); ++i) {
            if (images_[i].scenario == scenario) {
                return i;
            }
        }
        return std::nullopt;
    };
    for (const Block& block : blocks) {
        BlockReader comparison(block, nullptr);
        std::optional<std::string> first = comparison.reference(firstName);
        std::optional<std::string> second = comparison.reference(secondName);
        if (!first || !second) {
            continue;
        }
        std::optional<std::size_t> a = imageOf(*first);
        std::optional<std::size_t> b = imageOf(*second);
        if (!a || !b || (kind == RenderJobKind::Compare && !wirelineApplies(block, images_[*a]))) {
            continue;
        }
        if (series.pattern.find("{scenario}") == std::string::npos) {
            return Error{locationOf(*series.views, "output") + ": views '" + series.views->name +
                         "': the series makes the " + block.keyword + " image '" + block.name +
                         "', so its output template needs {scenario}"};
        }
        RenderJob job = images_[*a];
        job.kind = kind;
        job.scenario = block.name;
        job.first = *a;
        job.second = *b;
        Result<int> steps = kind == RenderJobKind::Blend ? blendSteps(series, block, job) : 1;
        if (!steps) {
            return steps.error();
        }
        for (int step = 0; step < steps.value(); ++step) {
            if (steps.value() > 1) {
                job.step = step;
                job.blendAmount = static_cast<double>(step) / (steps.value() - 1);
            }
            Result<std::string> name = ViewSeries::expandTemplate(series.pattern, job);
            if (!name) {
                return name.error();
            }
            comparisonVideos_.push_back(place(series, job, name.value()));
            comparisons_.push_back(job);
        }
    }
    return {};
}

Result<int> SeriesExpansion::blendSteps(const Series& series, const Block& block,
                                        RenderJob& job) const {
    // A blend sequence: `steps` images from t = 0 to 1.
    BlockReader reader(block, nullptr);
    job.blendAmount = reader.optionalNumber("amount").value_or(0.5);
    int steps = 1;
    if (std::optional<double> count = reader.optionalNumber("steps")) {
        if (*count != std::floor(*count)) {
            return Error{locationOf(block, "steps") + ": blend '" + block.name +
                         "': steps must be a whole number of images, got " +
                         std::to_string(*count)};
        }
        steps = static_cast<int>(*count);
    }
    if (steps > 1 && series.pattern.find("{step}") == std::string::npos &&
        series.pattern.find("{t}") == std::string::npos) {
        return Error{locationOf(*series.views, "output") + ": views '" + series.views->name +
                     "': the blend '" + block.name + "' is a sequence of " + std::to_string(steps) +
                     " images (steps), so the output template needs {step} or {t}"};
    }
    return steps;
}

VideoOf SeriesExpansion::place(const Series& series, RenderJob& job,
                               const std::string& name) const {
    job.output = outputFolder_ / name;
    if (!series.video) {
        return {};
    }
    const std::filesystem::path file = job.output;
    job.output = framePath(file, job.frame);
    return {file, series.views};
}

Result<std::vector<RenderJob>> SeriesExpansion::finish() {
    std::vector<RenderJob> jobs = std::move(images_);
    for (RenderJob& comparison : comparisons_) {
        jobs.push_back(std::move(comparison));
    }
    std::vector<VideoOf> videoFiles = std::move(imageVideos_);
    videoFiles.insert(videoFiles.end(), comparisonVideos_.begin(), comparisonVideos_.end());
    if (Status added = addVideos(jobs, videoFiles); !added) {
        return added.error();
    }
    if (Status distinct = checkOutputs(jobs); !distinct) {
        return distinct.error();
    }
    return jobs;
}

// One Video job per video file, after everything else, listing its frames in order.
Status SeriesExpansion::addVideos(std::vector<RenderJob>& jobs,
                                  const std::vector<VideoOf>& videoFiles) const {
    std::map<std::filesystem::path, std::size_t> videos;
    std::vector<RenderJob> videoJobs;
    auto describe = [](const RenderJob& job) {
        std::string text = job.path;  // appended piecewise: GCC 12 -Wrestrict misfires
        text.append(" ").append(job.scenario);
        if (job.time) {
            text.append(" ").append(job.time->text());
        }
        return text;
    };
    for (std::size_t i = 0; i < jobs.size(); ++i) {
        const auto& [file, views] = videoFiles[i];
        if (file.empty()) {
            continue;
        }
        auto [found, added] = videos.emplace(file, videoJobs.size());
        if (added) {
            RenderJob video = jobs[i];
            video.kind = RenderJobKind::Video;
            video.output = file;
            video.frames.clear();
            Result<CameraPath> path = CameraPath::fromBlock(*model_.findPath(jobs[i].path));
            SYLVA_CHECK(path.ok());  // checked when its frames were listed
            video.framesPerSecond = path.value().framesPerSecond();
            videoJobs.push_back(std::move(video));
        }
        RenderJob& video = videoJobs[found->second];
        const RenderJob& firstFrame = jobs[video.frames.empty() ? i : video.frames.front()];
        if (firstFrame.path != jobs[i].path || firstFrame.scenario != jobs[i].scenario ||
            describe(firstFrame) != describe(jobs[i])) {
            return Error{locationOf(*views, "output") + ": views '" + views->name +
                         "': two videos would be written to '" + file.string() + "' (" +
                         describe(firstFrame) + "; " + describe(jobs[i]) +
                         "); add {path}, {scenario} or {time} to the template"};
        }
        video.frames.push_back(i);
        jobs[i].video = jobs.size() + found->second;
    }
    for (RenderJob& video : videoJobs) {
        jobs.push_back(std::move(video));
    }
    return {};
}

Status SeriesExpansion::checkOutputs(std::vector<RenderJob>& jobs) const {
    auto describe = [](const RenderJob& job) {
        std::string text = job.path.empty()
                               ? "camera " + job.camera
                               : "path " + job.path + " frame " + std::to_string(job.frame);
        text += ", " + std::string(job.kind == RenderJobKind::Image ? "scenario " : "comparison ") +
                job.scenario;
        if (job.time) {
            text += ", time " + job.time->text();
        }
        return text;
    };
    std::map<std::filesystem::path, std::size_t> outputs;
    for (std::size_t i = 0; i < jobs.size(); ++i) {
        jobs[i].index = i;
        const std::filesystem::path normal = jobs[i].output.lexically_normal();
        auto [found, inserted] = outputs.emplace(normal, i);
        if (inserted) {
            continue;
        }
        const RenderJob& other = jobs[found->second];
        const Block* views = model_.findViews(jobs[i].view);
        return Error{(views ? locationOf(*views, "output") : model_.file.string()) + ": views '" +
                     jobs[i].view + "': two images would be written to '" + normal.string() +
                     "' (" + describe(other) + "; " + describe(jobs[i]) +
                     "); add {camera}, {scenario}, {time} or {frame} to the output template"};
    }
    return {};
}

}  // namespace

Result<std::string> ViewSeries::expandTemplate(const std::string& pattern, const RenderJob& job) {
    std::string out;
    for (std::size_t i = 0; i < pattern.size(); ++i) {
        if (pattern[i] != '{') {
            out += pattern[i];
            continue;
        }
        const std::size_t close = pattern.find('}', i);
        if (close == std::string::npos) {
            return Error{"unclosed '{' in output template '" + pattern + "'"};
        }
        const std::string token = pattern.substr(i + 1, close - i - 1);
        i = close;
        if (token == "view") {
            out += job.view;
        } else if (token == "camera") {
            out += job.path.empty() ? job.camera : job.path;
        } else if (token == "path") {
            out += job.path;
        } else if (token == "frame") {
            char text[16];
            std::snprintf(text, sizeof text, "%05d", std::max(job.frame, 0));
            out += text;
        } else if (token == "scenario") {
            out += job.scenario;
        } else if (token == "step") {
            if (job.step >= 0) {
                char text[16];
                std::snprintf(text, sizeof text, "%03d", job.step);
                out += text;
            }
        } else if (token == "t") {
            if (job.step >= 0) {
                char text[16];
                std::snprintf(text, sizeof text, "%.3f", job.blendAmount);
                out += text;
            }
        } else if (token == "time" || token.rfind("time:", 0) == 0) {
            if (!job.time) {
                continue;  // no times in this series: the token vanishes
            }
            const TimeFields f = fieldsOf(*job.time);
            if (token == "time") {
                out += f.year + "-" + f.month + "-" + f.day + "T" + f.hour + f.minute + f.zone;
                continue;
            }
            const std::string format = token.substr(5);
            for (std::size_t k = 0; k < format.size(); ++k) {
                if (format[k] != '%' || k + 1 == format.size()) {
                    out += format[k];
                    continue;
                }
                switch (format[++k]) {
                    case 'Y':
                        out += f.year;
                        break;
                    case 'm':
                        out += f.month;
                        break;
                    case 'd':
                        out += f.day;
                        break;
                    case 'H':
                        out += f.hour;
                        break;
                    case 'M':
                        out += f.minute;
                        break;
                    case 'S':
                        out += f.second;
                        break;
                    case 'z':
                        out += f.zone;
                        break;
                    case '%':
                        out += '%';
                        break;
                    default:
                        return Error{std::string("unknown time format '%") + format[k] +
                                     "' in output template '" + pattern +
                                     "' (known: %Y %m %d %H %M %S %z)"};
                }
            }
        } else {
            return Error{"unknown placeholder '{" + token + "}' in output template '" + pattern +
                         "' (known: {view} {camera} {path} {frame} {scenario} {step} {t} {time} "
                         "{time:FORMAT})"};
        }
    }
    return out;
}

Result<std::vector<RenderJob>> ViewSeries::expand(const ProjectModel& model,
                                                  const std::filesystem::path& outputFolder,
                                                  const std::string& viewsName) {
    std::vector<const Block*> viewBlocks;
    for (const Block& block : model.views) {
        if (viewsName.empty() || block.name == viewsName) {
            viewBlocks.push_back(&block);
        }
    }
    if (!viewsName.empty() && viewBlocks.empty()) {
        std::string known;
        for (const Block& block : model.views) {
            known += (known.empty() ? "" : ", ") + block.name;
        }
        return Error{model.file.string() + ": no views block named '" + viewsName + "'" +
                     (known.empty() ? "" : " (the project has: " + known + ")")};
    }
    if (viewBlocks.empty()) {
        return Error{model.file.string() + ": the project has no views block: nothing to render"};
    }
    SeriesExpansion expansion(model, outputFolder);
    for (const Block* views : viewBlocks) {
        if (Status added = expansion.add(*views); !added) {
            return added.error();
        }
    }
    return expansion.finish();
}

std::string ViewSeries::groupOf(const RenderJob& job) {
    // All frames of a video stay in one shard, which encodes them.
    return job.view + "\n" + job.camera + "\n" + job.path + "\n" +
           std::to_string(job.videoFrame ? -1 : job.frame) + "\n" +
           (job.time ? job.time->text() : std::string());
}

Result<std::pair<int, int>> ViewSeries::parseShard(const std::string& text) {
    int index = 0;
    int count = 0;
    char rest = 0;
    if (std::sscanf(text.c_str(), "%d/%d%c", &index, &count, &rest) != 2 || count < 1 ||
        index < 1 || index > count) {
        return Error{"--shard expects i/N with 1 <= i <= N (e.g. 2/4), got '" + text + "'"};
    }
    return std::pair<int, int>{index, count};
}

std::vector<RenderJob> ViewSeries::shard(const std::vector<RenderJob>& jobs, int index, int count) {
    SYLVA_CHECK(count >= 1 && index >= 1 && index <= count);
    // Contiguous blocks of groups: groups are numbered in order of first appearance, and
    // neighbouring groups are the same camera at other times or the next frames of a
    // path, which need the same tiles. Dealing them round-robin made every shard of the
    // Olinda series produce every camera's tiles.
    std::size_t groups = 0;
    for (const RenderJob& job : jobs) {
        groups = std::max(groups, job.group + 1);
    }
    const std::size_t shards = static_cast<std::size_t>(count);
    std::vector<RenderJob> mine;
    for (const RenderJob& job : jobs) {
        if (job.group * shards / std::max<std::size_t>(groups, 1) ==
            static_cast<std::size_t>(index - 1)) {
            mine.push_back(job);
        }
    }
    return mine;
}

}  // namespace sylva
