// `sylva render PROJECT [--views NAME] [--out DIR] [--size WxH] [--gl egl|osmesa|glfw]
//                       [--resume] [--shard i/N] [--progress auto|json|plain] [-D name=value]`
// Renders the view series of the project (or of one views block): cameras and path
// frames × scenarios × times (the sun from each time, NOAA), then the compare/blend
// images and a contact sheet per series. Every image is written atomically and
// recorded in a manifest; --resume skips images whose record matches; Ctrl-C stops
// after the current image. Exit code 0 only when every image was written.
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

#include "CommandLine.h"
#include "Commands.h"
#include "ImageJobs.h"
#include "ProjectSession.h"
#include "sylva/core/base/Hash.h"
#include "sylva/core/image/ContactSheet.h"
#include "sylva/core/image/ImageComparison.h"
#include "sylva/core/image/ImageWriter.h"
#include "sylva/core/scene/BlockReader.h"
#include "sylva/core/scene/CameraPath.h"
#include "sylva/core/scene/RenderManifest.h"
#include "sylva/core/scene/ViewSeries.h"
#include "sylva/core/tiles/Scheduler.h"
#include "sylva/render/GlContext.h"
#include "sylva/render/SceneRenderer.h"

namespace sylva::app {
namespace {

std::atomic<bool> interrupted{false};

void onInterrupt(int) {
    interrupted.store(true);
}

std::string kindName(RenderJobKind kind) {
    return kind == RenderJobKind::Image ? "image"
                                        : (kind == RenderJobKind::Compare ? "compare" : "blend");
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
                                                                   {"help", false}});
    if (command.has("help")) {
        std::puts(
            "usage: sylva render PROJECT [--views NAME] [--out DIR] [--size WxH] [--gl "
            "egl|osmesa|glfw]\n"
            "                    [--resume] [--shard i/N] [--progress auto|json|plain] [--cache-mb "
            "N]\n"
            "                    [-D name=value]");
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
    std::optional<render::GlBackend> backend;
    if (std::optional<std::string> gl = command.get("gl")) {
        Result<render::GlBackend> parsed = render::parseBackend(*gl);
        if (!parsed) {
            reportError("--gl: " + parsed.error().message);
            return 2;
        }
        backend = parsed.value();
    }
    std::size_t cacheMegabytes = 1024;
    if (std::optional<std::string> cache = command.get("cache-mb")) {
        const std::optional<std::size_t> parsed = parseCacheMegabytes(*cache);
        if (!parsed) {
            reportError("--cache-mb expects a tile cache budget in MiB within 16..1048576, got '" +
                        *cache + "'");
            return 2;
        }
        cacheMegabytes = *parsed;
    }
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
    const std::vector<RenderJob> jobs =
        shard.second > 1 ? ViewSeries::shard(allJobs, shard.first, shard.second) : allJobs;
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
    if (command.has("resume")) {
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

    // What decides a job's pixels, for --resume: the sources of its scenario (their
    // hashes cover parameters and the files they read), camera or path, settings, time.
    auto settingsHash = [&](ContentHash& hash) {
        hash.add(model.render.contentHash).add(settings.width).add(settings.height);
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
    std::map<std::size_t, std::uint64_t> jobHashes;  // by job index, for comparisons
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

        if (job.kind != RenderJobKind::Image) {
            // A comparison of two images of this series, read back from disk.
            ContentHash hash;
            hash.add(jobHashes[job.first])
                .add(jobHashes[job.second])
                .add(entry.kind)
                .add(job.scenario);
            const Block* block = nullptr;
            for (const Block& candidate :
                 job.kind == RenderJobKind::Compare ? model.compares : model.blends) {
                if (candidate.name == job.scenario) {
                    block = &candidate;
                }
            }
            SYLVA_CHECK(block != nullptr);
            hash.add(block->contentHash);
            entry.hash = hash.value();
            jobHashes[job.index] = entry.hash;
            if (command.has("resume") && manifest.isCurrent(relative, entry.hash)) {
                ++skipped;
                progress(job, 0.0, 0, true);
                continue;
            }
            RgbaImage first, second;
            Result<std::vector<std::uint8_t>> a =
                ImageWriter::readRgba8(allJobs[job.first].output, first.width, first.height);
            Result<std::vector<std::uint8_t>> b =
                ImageWriter::readRgba8(allJobs[job.second].output, second.width, second.height);
            if (!a || !b) {
                reportError(job.output.string() + ": cannot read the images to compare: " +
                            (!a ? a.error().message : b.error().message));
                ++failures;
                continue;
            }
            first.pixels = std::move(a.value());
            second.pixels = std::move(b.value());
            BlockReader reader(*block, SchemaRegistry::builtin().find(block->keyword));
            Result<RgbaImage> made = Error{"unknown comparison"};
            std::string firstName = allJobs[job.first].scenario;
            std::string secondName = allJobs[job.second].scenario;
            if (job.kind == RenderJobKind::Blend) {
                made = ImageComparison::blend(first, second,
                                              reader.optionalNumber("amount").value_or(0.5));
            } else {
                const Value* layout = reader.value("layout");
                const std::string mode =
                    layout && layout->get<Word>() ? layout->get<Word>()->text : "swipe";
                if (mode == "side_by_side") {
                    made = ImageComparison::sideBySide(first, second);
                } else if (mode == "difference") {
                    made = ImageComparison::difference(first, second);
                } else {
                    made = ImageComparison::swipe(first, second,
                                                  reader.optionalNumber("split").value_or(0.5));
                }
                if (made && reader.boolean("labels", true) && mode != "difference") {
                    ImageComparison::label(made.value(), firstName);
                    ImageComparison::label(made.value(), secondName, true);
                }
            }
            if (!made) {
                reportError(block->location.toString() + ": " + block->keyword + " '" +
                            block->name + "': " + made.error().message);
                ++failures;
                continue;
            }
            const Status written = ImageWriter::writeRgba8(
                job.output, made.value().width, made.value().height, made.value().pixels);
            if (!written) {
                reportError(written.error().message);
                ++failures;
                continue;
            }
            entry.seconds =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            manifest.record(entry);
            if (Status saved = manifest.save(); !saved) {
                reportError(saved.error().message);
            }
            if (!progressJson) {
                std::printf("%s  %dx%d  %.2f s  (%s of %s and %s)\n", job.output.string().c_str(),
                            made.value().width, made.value().height, entry.seconds,
                            entry.kind.c_str(), firstName.c_str(), secondName.c_str());
                std::fflush(stdout);
            }
            progress(job, entry.seconds, 0, false);
            continue;
        }

        const std::size_t tilesBefore = evaluator.totals().misses;
        // Each scenario renders its own model (overrides applied); unchanged sources
        // keep their content hashes, so their tiles come from the shared cache.
        Result<std::pair<const ProjectModel*, SourceGraph*>> scenario =
            session->forScenario(job.scenario);
        if (!scenario) {
            reportError(scenario.error().message);
            ++failures;
            continue;
        }
        Result<TerrainLayers> layers =
            scenario->second->terrainLayers(*scenario->first, job.scenario);
        if (!layers) {
            reportError(layers.error().message);
            ++failures;
            continue;
        }
        const Block* cameraBlock = job.camera.empty() ? nullptr : model.findCamera(job.camera);
        const Block* pathBlock = job.path.empty() ? nullptr : model.findPath(job.path);
        {
            ContentHash hash;
            settingsHash(hash);
            for (const Source* layer :
                 {layers.value().elevation, layers.value().color, layers.value().normals}) {
                hash.add(layer ? layer->contentHash() : 0ull);
            }
            hash.add(cameraBlock ? cameraBlock->contentHash : pathBlock->contentHash)
                .add(job.frame)
                .add(job.pathTime);
            hash.add(entry.time);
            entry.hash = hash.value();
            jobHashes[job.index] = entry.hash;
        }
        if (command.has("resume") && manifest.isCurrent(relative, entry.hash)) {
            ++skipped;
            progress(job, 0.0, 0, true);
            continue;
        }
        if (Status ready = ensureRenderer(); !ready) {
            reportError(ready.error().message);
            return 1;
        }
        Result<JobView> view = viewForJob(model, job, layers.value(), evaluator, setup, paths);
        if (!view) {
            reportError(view.error().message);
            ++failures;
            continue;
        }
        const std::string& what = view.value().what;
        settings.sunDirection = view.value().sun;
        Result<render::Image> image =
            renderer->render(layers.value(), evaluator, view.value().camera, settings);
        if (!image) {
            reportError(what + ": " + image.error().message);
            ++failures;
            continue;
        }
        const Status written =
            ImageWriter::writeRgba8(job.output, image->width, image->height, image->pixels);
        if (!written) {
            reportError(written.error().message);
            ++failures;
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
            entry.seconds = seconds;
            entry.tilesGenerated = tiles;
            manifest.record(entry);
            if (Status saved = manifest.save(); !saved) {
                reportError(saved.error().message);
            }
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
    // a shard sees part of it).
    if (shard.second == 1 && failures == 0) {
        std::map<std::string, std::vector<ContactSheetEntry>> sheets;
        for (const RenderJob& job : jobs) {
            RgbaImage image;
            Result<std::vector<std::uint8_t>> pixels =
                ImageWriter::readRgba8(job.output, image.width, image.height);
            if (!pixels) {
                continue;
            }
            image.pixels = std::move(pixels.value());
            std::string label =
                job.path.empty() ? job.camera : job.path + " #" + std::to_string(job.frame);
            label += " " + job.scenario;
            if (job.time) {
                label += " " + job.time->text().substr(11, 5);
            }
            sheets[job.view].push_back(
                {label,
                 ContactSheet::resize(image, 320,
                                      std::max(1, 320 * image.height / std::max(image.width, 1)))});
        }
        for (const auto& [view, entries] : sheets) {
            if (entries.size() < 2) {
                continue;
            }
            Result<RgbaImage> sheet = ContactSheet::build(entries, 320);
            const std::filesystem::path file = outputFolder / (view + "_contact_sheet.png");
            if (sheet && ImageWriter::writeRgba8(file, sheet.value().width, sheet.value().height,
                                                 sheet.value().pixels)) {
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
