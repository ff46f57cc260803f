// `sylva render PROJECT [--views NAME] [--out DIR] [--size WxH] [--gl egl|osmesa|glfw]
//                       [--resume] [--shard i/N] [--progress auto|json|plain] [--cache-mb N]
//                       [--no-comparisons] [-D name=value]`
// Renders the view series of the project (or of one views block): cameras and path
// frames × scenarios × times (the sun from each time, NOAA), then the compare/blend
// images, the MP4s of path series (frames encoded by ffmpeg) and a contact sheet per
// series. PNG outputs are 8-bit sRGB, EXR outputs linear half-float radiance (after
// exposure, before tone mapping); both carry metadata (camera, scenario, time, project,
// hashes, version). Every file is written atomically and recorded in a manifest;
// --resume skips images whose record matches; Ctrl-C stops after the current image.
// Exit code 0 only when every image was written.
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <tuple>

#include "CommandLine.h"
#include "Commands.h"
#include "ImageJobs.h"
#include "ProjectSession.h"
#include "sylva/core/base/Hash.h"
#include "sylva/core/image/ContactSheet.h"
#include "sylva/core/image/ImageComparison.h"
#include "sylva/core/image/ImageWriter.h"
#include "sylva/core/image/ToneMapping.h"
#include "sylva/core/model/BlockReader.h"
#include "sylva/core/scene/CameraPath.h"
#include "sylva/core/scene/RenderManifest.h"
#include "sylva/core/scene/ViewSeries.h"
#include "sylva/core/scheduler/Scheduler.h"
#include "sylva/render/gl/GlContext.h"
#include "sylva/render/scene/SceneRenderer.h"

namespace sylva::app {
namespace {

std::atomic<bool> interrupted{false};

void onInterrupt(int) {
    interrupted.store(true);
}

std::string kindName(RenderJobKind kind) {
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

std::string hexText(std::uint64_t value) {
    char text[20];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(value));
    return text;
}

// The full path of `program` on PATH, or empty.
std::string findOnPath(const std::string& program) {
    const char* path = std::getenv("PATH");
    std::stringstream folders(path ? path : "");
    std::string folder;
    while (std::getline(folders, folder, ':')) {
        const std::filesystem::path candidate =
            std::filesystem::path(folder.empty() ? "." : folder) / program;
        if (::access(candidate.c_str(), X_OK) == 0 && std::filesystem::is_regular_file(candidate)) {
            return candidate.string();
        }
    }
    return {};
}

// Runs `arguments` (no shell) with stdout/stderr into `log`; returns the exit status
// (-1 when it could not start).
int runProgram(const std::vector<std::string>& arguments, const std::filesystem::path& log) {
    const pid_t child = ::fork();
    if (child < 0) {
        return -1;
    }
    if (child == 0) {
        if (FILE* out = std::fopen(log.c_str(), "w")) {
            ::dup2(::fileno(out), STDOUT_FILENO);
            ::dup2(::fileno(out), STDERR_FILENO);
        }
        std::vector<char*> argv;
        for (const std::string& argument : arguments) {
            argv.push_back(const_cast<char*>(argument.c_str()));
        }
        argv.push_back(nullptr);
        ::execvp(argv[0], argv.data());
        ::_exit(127);
    }
    int status = 0;
    while (::waitpid(child, &status, 0) < 0) {
        if (errno != EINTR) {
            return -1;
        }
    }
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// Encodes the numbered PNG frames in `frames` into the MP4 `output` (H.264, yuv420p,
// `fps`) through a temporary file renamed into place. Odd sizes are padded by one
// pixel (yuv420p needs even ones).
Status encodeVideo(const std::string& ffmpeg, const std::filesystem::path& frames,
                   const std::filesystem::path& output, double fps) {
    const std::filesystem::path folder = output.has_parent_path() ? output.parent_path() : ".";
    const std::filesystem::path temporary =
        folder / (".sylva-" + std::to_string(::getpid()) + "-" + output.filename().string());
    const std::filesystem::path log = frames / "ffmpeg.log";
    char rate[32];
    std::snprintf(rate, sizeof rate, "%.6g", fps);
    const int status = runProgram({ffmpeg,
                                   "-nostdin",
                                   "-y",
                                   "-loglevel",
                                   "error",
                                   "-framerate",
                                   rate,
                                   "-start_number",
                                   "0",
                                   "-i",
                                   (frames / "%05d.png").string(),
                                   "-c:v",
                                   "libx264",
                                   "-pix_fmt",
                                   "yuv420p",
                                   "-vf",
                                   "pad=ceil(iw/2)*2:ceil(ih/2)*2",
                                   "-movflags",
                                   "+faststart",
                                   "-f",
                                   "mp4",
                                   temporary.string()},
                                  log);
    std::error_code error;
    if (status != 0) {
        std::ifstream stream(log);
        std::string text((std::istreambuf_iterator<char>(stream)), {});
        while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) {
            text.pop_back();
        }
        std::filesystem::remove(temporary, error);
        return Error{output.string() + ": ffmpeg failed (exit " + std::to_string(status) + ")" +
                     (text.empty() ? std::string() : ": " + text)};
    }
    std::filesystem::rename(temporary, output, error);
    if (error) {
        std::filesystem::remove(temporary, error);
        return Error{output.string() + ": cannot move the finished video into place"};
    }
    return {};
}

// An image of the series for composing: EXR as radiance, anything else 8-bit sRGB
// (shown as radiance through the inverse tone map when `linear`).
Result<RgbaImage> readDisplayed(const std::filesystem::path& path) {
    if (ImageWriter::isExr(path)) {
        Result<LinearImage> linear = ImageWriter::readLinear(path);
        if (!linear) {
            return linear.error();
        }
        return ToneMapping::display(linear.value());
    }
    RgbaImage image;
    Result<std::vector<std::uint8_t>> pixels =
        ImageWriter::readRgba8(path, image.width, image.height);
    if (!pixels) {
        return pixels.error();
    }
    image.pixels = std::move(pixels.value());
    return image;
}

Result<LinearImage> readRadiance(const std::filesystem::path& path) {
    if (ImageWriter::isExr(path)) {
        return ImageWriter::readLinear(path);
    }
    Result<RgbaImage> image = readDisplayed(path);
    if (!image) {
        return image.error();
    }
    LinearImage out(image.value().width, image.value().height);
    for (std::size_t i = 0; i < out.pixels.size(); ++i) {
        out.pixels[i] = i % 4 == 3 ? image.value().pixels[i] / 255.0f
                                   : ToneMapping::radiance(image.value().pixels[i]);
    }
    return out;
}

// The comparison image of `job` from its two inputs (RgbaImage or LinearImage).
template <typename Image>
Result<Image> compose(const RenderJob& job, BlockReader& reader, const Image& first,
                      const Image& second, const std::string& firstName,
                      const std::string& secondName) {
    if (job.kind == RenderJobKind::Blend) {
        return ImageComparison::blend(first, second, job.blendAmount);
    }
    const Value* layout = reader.value("layout");
    const std::string mode = layout && layout->get<Word>() ? layout->get<Word>()->text : "swipe";
    Result<Image> made = Error{"unknown comparison"};
    if (mode == "side_by_side") {
        made = ImageComparison::sideBySide(first, second);
    } else if (mode == "difference") {
        made = ImageComparison::difference(first, second);
    } else {
        made = ImageComparison::swipe(first, second, reader.optionalNumber("split").value_or(0.5));
    }
    if (made && reader.boolean("labels", true) && mode != "difference") {
        ImageComparison::label(made.value(), firstName);
        ImageComparison::label(made.value(), secondName, true);
    }
    return made;
}

// "today/beach_0900.png" relative to the output folder (for the manifest).
std::string relativeOutput(const std::filesystem::path& output,
                           const std::filesystem::path& folder) {
    return output.lexically_normal().lexically_relative(folder.lexically_normal()).generic_string();
}

std::string jsonText(const std::string& text) {
    std::string out = "\"";
    for (char c : text) {
        if (c == '"' || c == '\\') {
            out += '\\';
        }
        out += c;
    }
    return out + "\"";
}

// Checks that `folder` exists (creating it) and accepts files, before any rendering.
bool checkWritable(const std::filesystem::path& folder) {
    std::error_code error;
    std::filesystem::create_directories(folder, error);
    if (error) {
        reportError("cannot create output folder '" + folder.string() + "': " + error.message());
        return false;
    }
    const std::filesystem::path probe =
        folder / (".sylva-write-test-" + std::to_string(::getpid()));
    {
        std::ofstream stream(probe);
        if (!stream) {
            reportError("cannot write to output folder '" + folder.string() +
                        "': permission denied or read-only");
            return false;
        }
    }
    std::filesystem::remove(probe, error);
    return true;
}

}  // namespace

int runRender(const std::vector<std::string>& arguments) {
    const ParsedCommandLine command = parseCommandLine(arguments, {{"views"},
                                                                   {"out"},
                                                                   {"size"},
                                                                   {"gl"},
                                                                   {"shard"},
                                                                   {"progress"},
                                                                   {"cache-mb"},
                                                                   {"resume", false},
                                                                   {"no-comparisons", false},
                                                                   {"help", false}});
    if (command.has("help")) {
        std::puts(
            "usage: sylva render PROJECT [--views NAME] [--out DIR] [--size WxH] [--gl "
            "egl|osmesa|glfw]\n"
            "                    [--resume] [--shard i/N] [--progress auto|json|plain] [--cache-mb "
            "N]\n"
            "                    [--no-comparisons] [-D name=value]\n"
            "Outputs by the views' template extension: .png (8-bit sRGB), .exr (linear radiance,\n"
            "half float), .mp4 (path frames encoded by ffmpeg). --no-comparisons renders only the\n"
            "scenario images (no compare/blend images, no contact sheets).");
        return 0;
    }
    if (!command.error.empty() || command.positional.size() != 1) {
        reportError(command.error.empty()
                        ? "render needs exactly one project file (see 'sylva render --help')"
                        : command.error);
        return 2;
    }
    int overrideWidth = 0, overrideHeight = 0;
    if (std::optional<std::string> size = command.get("size");
        size && !parseSize(*size, overrideWidth, overrideHeight)) {
        reportError("--size expects WIDTHxHEIGHT within 1..16384, got '" + *size + "'");
        return 2;
    }
    Result<std::optional<render::GlBackend>> glOption = glBackendOption(command);
    if (!glOption) {
        reportError(glOption.error().message);
        return 2;
    }
    const std::optional<render::GlBackend> backend = glOption.value();
    const Result<std::optional<std::size_t>> cacheOption = cacheMegabytesOption(command);
    if (!cacheOption) {
        reportError(cacheOption.error().message);
        return 2;
    }
    const std::optional<std::size_t> cacheOverride = cacheOption.value();
    std::pair<int, int> shard{1, 1};
    if (std::optional<std::string> text = command.get("shard")) {
        Result<std::pair<int, int>> parsed = ViewSeries::parseShard(*text);
        if (!parsed) {
            reportError(parsed.error().message);
            return 2;
        }
        shard = parsed.value();
    }
    const std::string progressMode = command.get("progress").value_or("auto");
    if (progressMode != "auto" && progressMode != "json" && progressMode != "plain") {
        reportError("--progress expects auto, json or plain, got '" + progressMode + "'");
        return 2;
    }
    const bool progressJson = progressMode == "json";
    const bool progressBar = progressMode == "auto" && ::isatty(STDERR_FILENO);
    const bool resume = command.has("resume");

    std::optional<ProjectSession> session =
        ProjectSession::open(command.positional[0], command.defines);
    if (!session) {
        return 1;
    }
    const ProjectModel& model = session->model;

    // Every job and its output path, before touching GL or the disk.
    const std::filesystem::path outputFolder = command.get("out").value_or("out");
    Result<std::vector<RenderJob>> expanded =
        ViewSeries::expand(model, outputFolder, command.get("views").value_or(""));
    if (!expanded) {
        reportError(expanded.error().message);
        return 1;
    }
    const std::vector<RenderJob>& allJobs = expanded.value();
    std::vector<RenderJob> jobs =
        shard.second > 1 ? ViewSeries::shard(allJobs, shard.first, shard.second) : allJobs;
    if (command.has("no-comparisons")) {
        std::erase_if(jobs, [&](const RenderJob& job) {
            const RenderJobKind kind =
                job.kind == RenderJobKind::Video ? allJobs[job.frames.front()].kind : job.kind;
            return kind == RenderJobKind::Compare || kind == RenderJobKind::Blend;
        });
    }
    // Render order: the images of one viewpoint and scenario at all its times one after
    // another (the sun changes only the shading, so later times find every tile still
    // cached; with scenarios alternating, a large scenario's tiles push the other's out
    // of the budget). Comparisons and videos keep their place after the images.
    {
        std::map<std::string, std::size_t> firstSeen;
        auto rank = [&](const std::string& key, std::size_t index) {
            return firstSeen.emplace(key, index).first->second;
        };
        std::map<std::size_t, std::tuple<std::size_t, std::size_t, std::size_t>> order;
        for (const RenderJob& job : jobs) {
            const std::string viewpoint =
                job.view + "\n" + job.camera + "\n" + job.path + "\n" + std::to_string(job.frame);
            order[job.index] =
                job.kind == RenderJobKind::Image
                    ? std::make_tuple(rank(viewpoint, job.index),
                                      rank(viewpoint + "\n" + job.scenario, job.index), job.index)
                    : std::make_tuple(allJobs.size(), allJobs.size(), job.index);
        }
        std::stable_sort(jobs.begin(), jobs.end(), [&](const RenderJob& a, const RenderJob& b) {
            return order.at(a.index) < order.at(b.index);
        });
    }
    // MP4 outputs need ffmpeg: say so before rendering anything.
    std::string ffmpeg;
    for (const RenderJob& job : jobs) {
        if (job.kind == RenderJobKind::Video && ffmpeg.empty()) {
            ffmpeg = findOnPath("ffmpeg");
            if (ffmpeg.empty()) {
                const Block* views = model.findViews(job.view);
                const Attribute* output = views ? views->find("output") : nullptr;
                reportError((output ? output->location.toString() : model.file.string()) +
                            ": views '" + job.view + "': writing MP4 (" +
                            relativeOutput(job.output, outputFolder) +
                            ") needs ffmpeg on PATH; install it (apt install ffmpeg) or output "
                            "PNG frames (e.g. output = \"{path}/{frame}.png\")");
                return 1;
            }
        }
    }
    for (const RenderJob& job : jobs) {
        const std::filesystem::path folder =
            job.output.has_parent_path() ? job.output.parent_path() : ".";
        if (!checkWritable(folder)) {
            return 1;
        }
    }
    // Paths are checked (keys, heights) before the first image, too.
    std::map<std::string, CameraPath> paths;
    for (const RenderJob& job : jobs) {
        if (!job.path.empty() && !paths.count(job.path)) {
            Result<CameraPath> path = CameraPath::fromBlock(*model.findPath(job.path));
            if (!path) {
                reportError(path.error().message);
                return 1;
            }
            paths.emplace(job.path, std::move(path.value()));
        }
    }
    // Shards keep their own manifest, so parallel processes never write one file.
    RenderManifest manifest(outputFolder /
                            (shard.second > 1 ? "manifest.shard-" + std::to_string(shard.first) +
                                                    "-of-" + std::to_string(shard.second) + ".json"
                                              : std::string("manifest.json")));
    if (resume) {
        if (Status loaded = manifest.load(); !loaded) {
            reportError(loaded.error().message);
            return 1;
        }
    }

    Result<RenderSetup> madeSetup = makeRenderSetup(model, overrideWidth, overrideHeight);
    if (!madeSetup) {
        reportError(madeSetup.error().message);
        return 1;
    }
    const RenderSetup setup = madeSetup.value();
    render::RenderSettings settings = setup.settings;
    const render::TerrainSettings terrainSettings = setup.terrain;
    const std::size_t cacheMegabytes = cacheOverride.value_or(setup.cacheMegabytes);

    // The project as a whole (every block), for the images' metadata.
    std::uint64_t projectHash = 0;
    {
        ContentHash hash;
        hash.add(model.render.contentHash).add(model.project.contentHash);
        for (const std::vector<Block>* blocks :
             {&model.sources, &model.scenarios, &model.cameras, &model.views, &model.compares,
              &model.blends, &model.paths, &model.params}) {
            for (const Block& block : *blocks) {
                hash.add(block.name).add(block.contentHash);
            }
        }
        projectHash = hash.value();
    }
    const std::string projectPath =
        std::filesystem::absolute(model.file).lexically_normal().string();

    // What decides each job's pixels, for --resume and the metadata, computed before
    // rendering (a scenario that cannot be built is an error before any image): the
    // sources of its scenario (their hashes cover parameters and the files they read),
    // camera or path frame, settings and time; comparisons and videos combine theirs.
    std::map<std::size_t, std::uint64_t> jobHashes;  // by job index
    std::map<std::size_t, TerrainLayers> jobLayers;
    for (const RenderJob& job : jobs) {
        ContentHash hash;
        if (job.kind == RenderJobKind::Image) {
            Result<std::pair<const ProjectModel*, SourceGraph*>> scenario =
                session->forScenario(job.scenario);
            if (!scenario) {
                reportError(scenario.error().message);
                return 1;
            }
            Result<TerrainLayers> layers =
                scenario->second->terrainLayers(*scenario->first, job.scenario);
            if (!layers) {
                reportError(layers.error().message);
                return 1;
            }
            const Block* cameraBlock = job.camera.empty() ? nullptr : model.findCamera(job.camera);
            const Block* pathBlock = job.path.empty() ? nullptr : model.findPath(job.path);
            hash.add(model.render.contentHash).add(settings.width).add(settings.height);
            for (const Source* layer :
                 {layers.value().elevation, layers.value().color, layers.value().normals}) {
                hash.add(layer ? layer->contentHash() : 0ull);
            }
            hash.add(cameraBlock ? cameraBlock->contentHash : pathBlock->contentHash)
                .add(job.frame)
                .add(job.pathTime)
                .add(job.time ? job.time->text() : std::string());
            hash.add(ImageWriter::isExr(job.output));
            jobLayers.emplace(job.index, layers.value());
        } else if (job.kind == RenderJobKind::Video) {
            hash.add(std::string("video")).add(job.framesPerSecond);
            for (std::size_t frame : job.frames) {
                hash.add(jobHashes[frame]);
            }
        } else {
            const std::vector<Block>& blocks =
                job.kind == RenderJobKind::Compare ? model.compares : model.blends;
            const auto block = std::find_if(blocks.begin(), blocks.end(),
                                            [&](const Block& b) { return b.name == job.scenario; });
            SYLVA_CHECK(block != blocks.end());
            hash.add(jobHashes[job.first])
                .add(jobHashes[job.second])
                .add(kindName(job.kind))
                .add(job.scenario)
                .add(block->contentHash)
                .add(job.blendAmount);
        }
        jobHashes[job.index] = hash.value();
    }
    auto metadataFor = [&](const RenderJob& job) {
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
                         allJobs[job.first].scenario + " | " + allJobs[job.second].scenario);
            if (job.kind == RenderJobKind::Blend) {
                char amount[32];
                std::snprintf(amount, sizeof amount, "%.6g", job.blendAmount);
                metadata.set("sylva:blend_amount", amount);
            }
        }
        if (job.time) {
            metadata.set("sylva:time", job.time->text());
        }
        metadata.set("sylva:project", projectPath);
        metadata.set("sylva:project_hash", hexText(projectHash));
        metadata.set("sylva:image_hash", hexText(jobHashes[job.index]));
        metadata.set("sylva:exposure", std::to_string(settings.exposure));
        metadata.set("sylva:version", SYLVA_VERSION);
        return metadata;
    };

    std::signal(SIGINT, onInterrupt);
    std::signal(SIGTERM, onInterrupt);

    std::unique_ptr<render::GlContext> context;
    std::unique_ptr<render::SceneRenderer> renderer;
    const render::ShaderLibrary library;
    auto ensureRenderer = [&]() -> Status {
        if (renderer) {
            return {};
        }
        render::ContextOptions contextOptions;
        contextOptions.backend = backend;
        Result<std::unique_ptr<render::GlContext>> created =
            render::GlContext::create(contextOptions);
        if (!created) {
            return created.error();
        }
        context = std::move(created.value());
        Result<std::unique_ptr<render::SceneRenderer>> made =
            render::SceneRenderer::create(library, terrainSettings);
        if (!made) {
            return made.error();
        }
        renderer = std::move(made.value());
        return {};
    };
    // Tiles come from the concurrent scheduler (one worker per core); every image
    // waits for all its levels (RenderSettings::waitForTiles), so output does not
    // depend on thread timing.
    SchedulerOptions schedulerOptions;
    schedulerOptions.format = TileFormat{terrainSettings.clipmapSize, 2};
    schedulerOptions.budgetBytes = cacheMegabytes << 20;
    Scheduler evaluator(schedulerOptions);

    int failures = 0;
    int degraded = 0;
    int skipped = 0;
    std::set<std::size_t> failedJobs;
    const auto seriesStart = std::chrono::steady_clock::now();
    std::size_t done = 0;
    auto progress = [&](const RenderJob& job, double seconds, std::size_t tiles, bool skippedJob) {
        ++done;
        const double elapsed =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - seriesStart).count();
        const double eta =
            done > 0 ? elapsed / static_cast<double>(done) * static_cast<double>(jobs.size() - done)
                     : 0;
        if (progressJson) {
            std::printf(
                "{\"event\": \"image\", \"index\": %zu, \"total\": %zu, \"output\": %s, \"kind\": "
                "\"%s\", "
                "\"skipped\": %s, \"seconds\": %.3f, \"tiles\": %zu, \"eta_s\": %.1f}\n",
                done, jobs.size(), jsonText(job.output.string()).c_str(),
                kindName(job.kind).c_str(), skippedJob ? "true" : "false", seconds, tiles, eta);
            std::fflush(stdout);
            return;
        }
        if (progressBar) {
            const int width = 30;
            const int filled =
                static_cast<int>(width * done / std::max<std::size_t>(jobs.size(), 1));
            std::fprintf(stderr, "\r[%s%s] %zu/%zu  ETA %4.0f s  ",
                         std::string(static_cast<std::size_t>(filled), '#').c_str(),
                         std::string(static_cast<std::size_t>(width - filled), '.').c_str(), done,
                         jobs.size(), eta);
            if (done == jobs.size()) {
                std::fputc('\n', stderr);
            }
            std::fflush(stderr);
        }
    };
    auto fail = [&](const RenderJob& job, const std::string& message) {
        reportError(message);
        ++failures;
        failedJobs.insert(job.index);
    };
    auto record = [&](ManifestEntry& entry, const std::chrono::steady_clock::time_point start) {
        entry.seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        manifest.record(entry);
        if (Status saved = manifest.save(); !saved) {
            reportError(saved.error().message);
        }
    };
    // A video whose file is current needs none of its frames.
    auto videoIsCurrent = [&](const RenderJob& job) {
        return resume && job.video &&
               manifest.isCurrent(relativeOutput(allJobs[*job.video].output, outputFolder),
                                  jobHashes[*job.video]);
    };

    for (const RenderJob& job : jobs) {
        if (interrupted.load()) {
            break;
        }
        const auto start = std::chrono::steady_clock::now();
        const std::string relative = relativeOutput(job.output, outputFolder);
        ManifestEntry entry;
        entry.output = relative;
        entry.kind = kindName(job.kind);
        entry.view = job.view;
        entry.camera = job.camera;
        entry.path = job.path;
        entry.frame = job.frame;
        entry.scenario = job.scenario;
        entry.time = job.time ? job.time->text() : "";
        entry.hash = jobHashes[job.index];
        if ((resume && manifest.isCurrent(relative, entry.hash)) || videoIsCurrent(job)) {
            ++skipped;
            progress(job, 0.0, 0, true);
            continue;
        }

        if (job.kind == RenderJobKind::Video) {
            if (std::any_of(job.frames.begin(), job.frames.end(),
                            [&](std::size_t frame) { return failedJobs.count(frame) > 0; })) {
                fail(job, job.output.string() + ": not encoded: some of its frames failed");
                continue;
            }
            const std::filesystem::path frames = allJobs[job.frames.front()].output.parent_path();
            if (Status encoded = encodeVideo(ffmpeg, frames, job.output, job.framesPerSecond);
                !encoded) {
                fail(job, encoded.error().message);
                continue;
            }
            // The frames were only the video's input.
            std::error_code ignored;
            std::filesystem::remove_all(frames, ignored);
            entry.frame = static_cast<int>(job.frames.size());
            record(entry, start);
            if (!progressJson) {
                std::printf("%s  %zu frames at %g fps  %.2f s\n", job.output.string().c_str(),
                            job.frames.size(), job.framesPerSecond, entry.seconds);
                std::fflush(stdout);
            }
            progress(job, entry.seconds, 0, false);
            continue;
        }

        if (job.kind != RenderJobKind::Image) {
            // A comparison of two images of this series, read back from disk; EXR
            // outputs are composed in linear radiance.
            const Block* block = nullptr;
            for (const Block& candidate :
                 job.kind == RenderJobKind::Compare ? model.compares : model.blends) {
                if (candidate.name == job.scenario) {
                    block = &candidate;
                }
            }
            SYLVA_CHECK(block != nullptr);
            BlockReader reader(*block, SchemaRegistry::builtin().find(block->keyword));
            const std::string& firstName = allJobs[job.first].scenario;
            const std::string& secondName = allJobs[job.second].scenario;
            const std::filesystem::path& firstFile = allJobs[job.first].output;
            const std::filesystem::path& secondFile = allJobs[job.second].output;
            // Reads both scenario images (radiance for EXR, displayed pixels otherwise),
            // composes them and writes the result; false after reporting a failure.
            Status written;
            int width = 0, height = 0;
            const auto composeFiles = [&](const auto& read, const auto& write) {
                const auto a = read(firstFile);
                const auto b = read(secondFile);
                if (!a || !b) {
                    fail(job, job.output.string() + ": cannot read the images to compare: " +
                                  (!a ? a.error().message : b.error().message));
                    return false;
                }
                const auto made = compose(job, reader, a.value(), b.value(), firstName, secondName);
                if (!made) {
                    fail(job, block->location.toString() + ": " + block->keyword + " '" +
                                  block->name + "': " + made.error().message);
                    return false;
                }
                width = made.value().width;
                height = made.value().height;
                written = write(made.value());
                return true;
            };
            const bool composed =
                ImageWriter::isExr(job.output)
                    ? composeFiles(readRadiance,
                                   [&](const LinearImage& image) {
                                       return ImageWriter::writeLinear(job.output, image,
                                                                       metadataFor(job));
                                   })
                    : composeFiles(readDisplayed, [&](const RgbaImage& image) {
                          return ImageWriter::writeRgba8(job.output, image.width, image.height,
                                                         image.pixels, metadataFor(job));
                      });
            if (!composed) {
                continue;
            }
            if (!written) {
                fail(job, written.error().message);
                continue;
            }
            record(entry, start);
            if (!progressJson) {
                std::printf("%s  %dx%d  %.2f s  (%s of %s and %s)\n", job.output.string().c_str(),
                            width, height, entry.seconds, entry.kind.c_str(), firstName.c_str(),
                            secondName.c_str());
                std::fflush(stdout);
            }
            progress(job, entry.seconds, 0, false);
            continue;
        }

        const std::size_t tilesBefore = evaluator.totals().misses;
        // Each scenario renders its own model (overrides applied); unchanged sources
        // keep their content hashes, so their tiles come from the shared cache.
        const TerrainLayers& layers = jobLayers.at(job.index);
        if (Status ready = ensureRenderer(); !ready) {
            reportError(ready.error().message);
            return 1;
        }
        Result<JobView> view = viewForJob(model, job, layers, evaluator, setup, paths);
        if (!view) {
            fail(job, view.error().message);
            continue;
        }
        const std::string& what = view.value().what;
        settings.sunDirection = view.value().sun;
        settings.linearOutput = ImageWriter::isExr(job.output);
        Result<render::Image> image =
            renderer->render(layers, evaluator, view.value().camera, settings);
        if (!image) {
            fail(job, what + ": " + image.error().message);
            continue;
        }
        const Status written = writeRenderedImage(job.output, image.value(), metadataFor(job));
        if (!written) {
            fail(job, written.error().message);
            continue;
        }
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        const render::RenderStatistics& stats = renderer->statistics();
        const std::size_t tiles = evaluator.totals().misses - tilesBefore;
        if (!stats.terrain.degraded.empty()) {
            // The image is written (coarser data is better than none), but the exit
            // status must say that data was missing.
            reportError(what + ": drawn with coarser terrain: " + stats.terrain.degraded);
            ++degraded;
        } else {
            entry.tilesGenerated = tiles;
            record(entry, start);
        }
        if (!progressJson) {
            std::printf("%s  %dx%d  %.2f s  (levels %d-%d, %llu triangles, %zu tiles)\n",
                        job.output.string().c_str(), image->width, image->height, seconds,
                        stats.terrain.levels.coarsest, stats.terrain.levels.finest,
                        static_cast<unsigned long long>(stats.terrain.triangles), tiles);
            std::fflush(stdout);
        }
        progress(job, seconds, tiles, false);
    }
    std::signal(SIGINT, SIG_DFL);
    std::signal(SIGTERM, SIG_DFL);
    if (interrupted.load()) {
        reportError("interrupted: " + std::to_string(done) + " of " + std::to_string(jobs.size()) +
                    " images done; run again with --resume to finish");
        return 130;
    }

    // A contact sheet per views block with more than one image (whole series only:
    // a shard sees part of it; videos and their frames are not shown).
    if (shard.second == 1 && failures == 0 && !command.has("no-comparisons")) {
        std::map<std::string, std::vector<ContactSheetEntry>> sheets;
        for (const RenderJob& job : jobs) {
            if (job.kind == RenderJobKind::Video || job.video) {
                continue;
            }
            Result<RgbaImage> image = readDisplayed(job.output);
            if (!image) {
                continue;
            }
            std::string label =
                job.path.empty() ? job.camera : job.path + " #" + std::to_string(job.frame);
            label += " " + job.scenario;
            if (job.step >= 0) {
                char text[16];
                std::snprintf(text, sizeof text, " t=%.2f", job.blendAmount);
                label += text;
            }
            if (job.time) {
                label += " " + job.time->text().substr(11, 5);
            }
            const int width = image.value().width;
            const int height = image.value().height;
            sheets[job.view].push_back(
                {label, ContactSheet::resize(image.value(), 320,
                                             std::max(1, 320 * height / std::max(width, 1)))});
        }
        for (const auto& [view, entries] : sheets) {
            if (entries.size() < 2) {
                continue;
            }
            Result<RgbaImage> sheet = ContactSheet::build(entries, 320);
            const std::filesystem::path file = outputFolder / (view + "_contact_sheet.png");
            ImageMetadata metadata;
            metadata.set("sylva:view", view);
            metadata.set("sylva:project", projectPath);
            metadata.set("sylva:project_hash", hexText(projectHash));
            metadata.set("sylva:version", SYLVA_VERSION);
            if (sheet && ImageWriter::writeRgba8(file, sheet.value().width, sheet.value().height,
                                                 sheet.value().pixels, metadata)) {
                if (!progressJson) {
                    std::printf("%s  contact sheet of %zu images\n", file.string().c_str(),
                                entries.size());
                }
            }
        }
    }
    if (progressJson) {
        std::printf(
            "{\"event\": \"done\", \"total\": %zu, \"skipped\": %d, \"failed\": %d, \"degraded\": "
            "%d}\n",
            jobs.size(), skipped, failures, degraded);
    }
    if (failures > 0) {
        reportError(std::to_string(failures) + " of " + std::to_string(jobs.size()) +
                    " images could not be rendered");
        return 1;
    }
    if (degraded > 0) {
        reportError(std::to_string(degraded) + " of " + std::to_string(jobs.size()) +
                    " images were rendered with missing data");
        return 1;
    }
    return 0;
}

}  // namespace sylva::app
