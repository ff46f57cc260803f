// `sylva watch PROJECT [--views NAME] [--camera NAME] [--out DIR] [--size WxH] [--gl ...]
//                      [--interval-ms N] [--exit-after N] [-D name=value]`
// Headless edit loop: renders the chosen views, then watches the project file, its
// imports and every data file its sources read. On a change it re-checks the project;
// with errors it prints the diagnostics and keeps the last images; otherwise it keeps
// the tiles of every source whose content hash is unchanged (Scheduler::retainOnly),
// recomputes only the rest, rewrites the images and prints the edit-to-image latency
// with the number of tiles recomputed.
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <memory>
#include <thread>
#include <unordered_set>

#include "CommandLine.h"
#include "Commands.h"
#include "ImageJobs.h"
#include "ProjectSession.h"
#include "sylva/core/base/FileWatch.h"
#include "sylva/core/image/ImageWriter.h"
#include "sylva/core/scheduler/Scheduler.h"
#include "sylva/render/gl/GlContext.h"

namespace sylva::app {
namespace {

std::atomic<bool> stopWatching{false};
void onStop(int) {
    stopWatching.store(true);
}

struct Loaded {
    std::optional<ProjectSession> session;
    std::vector<std::filesystem::path> projectFiles;
};

// Loads the project; on errors prints them and returns no session (but the files read,
// so the watch goes on).
Loaded load(const std::filesystem::path& file, const ParsedCommandLine& command) {
    Loaded loaded;
    dsl::LoadResult probe = dsl::loadProject(file, loadOptionsFor(command));
    loaded.projectFiles = probe.files;
    if (loaded.projectFiles.empty()) {
        loaded.projectFiles.push_back(file);
    }
    if (probe.hasErrors() || !probe.model) {
        printDiagnostics(probe);
        return loaded;
    }
    loaded.session = ProjectSession::open(file, command.defines);
    return loaded;
}

}  // namespace

int runWatch(const std::vector<std::string>& arguments) {
    const ParsedCommandLine command = parseCommandLine(arguments, {{"views"},
                                                                   {"camera"},
                                                                   {"out"},
                                                                   {"size"},
                                                                   {"gl"},
                                                                   {"interval-ms"},
                                                                   {"exit-after"},
                                                                   {"cache-mb"},
                                                                   {"help", false}});
    if (command.has("help")) {
        std::puts(
            "usage: sylva watch PROJECT [--views NAME] [--camera NAME] [--out DIR] [--size WxH]\n"
            "                   [--gl egl|osmesa|glfw] [--interval-ms N] [--exit-after N] "
            "[--cache-mb N]\n"
            "                   [-D name=value]");
        return 0;
    }
    if (!command.error.empty() || command.positional.size() != 1) {
        reportError(command.error.empty()
                        ? "watch needs exactly one project file (see 'sylva watch --help')"
                        : command.error);
        return 2;
    }
    auto positiveInt = [&](const char* name, int fallback, int& out) {
        out = fallback;
        if (std::optional<std::string> text = command.get(name)) {
            char* end = nullptr;
            const long value = std::strtol(text->c_str(), &end, 10);
            if (end == text->c_str() || *end != '\0' || value < 1 || value > 100000000) {
                reportError(std::string("--") + name + " expects a positive whole number, got '" +
                            *text + "'");
                return false;
            }
            out = static_cast<int>(value);
        }
        return true;
    };
    int intervalMs = 0, exitAfter = 0;
    if (!positiveInt("interval-ms", 200, intervalMs) ||
        !positiveInt("exit-after", 1 << 30, exitAfter)) {
        return 2;
    }
    int overrideWidth = 0, overrideHeight = 0;
    if (std::optional<std::string> size = command.get("size");
        size && !parseSize(*size, overrideWidth, overrideHeight)) {
        reportError("--size expects WIDTHxHEIGHT within 1..16384, got '" + *size + "'");
        return 2;
    }
    // The budget: --cache-mb, else the render block's cache_mb (read on the first load).
    const Result<std::optional<std::size_t>> cacheOption = cacheMegabytesOption(command);
    if (!cacheOption) {
        reportError(cacheOption.error().message);
        return 2;
    }
    std::optional<std::size_t> cacheMegabytes = cacheOption.value();
    render::ContextOptions contextOptions;
    Result<std::optional<render::GlBackend>> backend = glBackendOption(command);
    if (!backend) {
        reportError(backend.error().message);
        return 2;
    }
    contextOptions.backend = backend.value();
    const std::filesystem::path projectFile = command.positional[0];
    const std::filesystem::path outputFolder = command.get("out").value_or("out");
    const std::string viewsName = command.get("views").value_or("");
    const std::optional<std::string> cameraName = command.get("camera");

    Result<std::unique_ptr<render::GlContext>> context = render::GlContext::create(contextOptions);
    if (!context) {
        reportError(context.error().message);
        return 1;
    }
    const render::ShaderLibrary library;
    SchedulerOptions schedulerOptions;
    std::unique_ptr<Scheduler> scheduler;
    std::unique_ptr<render::SceneRenderer> renderer;

    std::signal(SIGINT, onStop);
    std::signal(SIGTERM, onStop);
    Loaded current = load(projectFile, command);
    FileWatch watch;
    int renders = 0;
    int status = 0;
    auto startWatching = [&](const Loaded& loaded) {
        watch.clear();
        for (const std::filesystem::path& file : loaded.projectFiles) {
            watch.watch(file);
        }
        if (loaded.session) {
            for (const auto& [scenario, graph] : loaded.session->scenarioGraphs) {
                for (const std::filesystem::path& file : graph.files()) {
                    watch.watch(file);
                }
            }
            if (loaded.session->graph) {
                for (const std::filesystem::path& file : loaded.session->graph->files()) {
                    watch.watch(file);
                }
            }
        }
    };
    // Renders the chosen jobs of `session`; returns false on errors (already printed).
    auto renderAll = [&](ProjectSession& session, std::chrono::steady_clock::time_point since) {
        Result<std::vector<RenderJob>> jobs =
            ViewSeries::expand(session.model, outputFolder, viewsName);
        if (!jobs) {
            reportError(jobs.error().message);
            return false;
        }
        Result<RenderSetup> setup = makeRenderSetup(session.model, overrideWidth, overrideHeight);
        if (!setup) {
            reportError(setup.error().message);
            return false;
        }
        if (!scheduler) {
            schedulerOptions.format = TileFormat{setup.value().terrain.clipmapSize, 2};
            schedulerOptions.budgetBytes = cacheMegabytes.value_or(setup.value().cacheMegabytes)
                                           << 20;
            scheduler = std::make_unique<Scheduler>(schedulerOptions);
            Result<std::unique_ptr<render::SceneRenderer>> made =
                render::SceneRenderer::create(library, setup.value().terrain);
            if (!made) {
                reportError(made.error().message);
                return false;
            }
            renderer = std::move(made.value());
        }
        std::map<std::string, CameraPath> paths;
        const std::size_t tilesBefore = scheduler->totals().misses;
        int images = 0;
        bool ok = true;
        for (const RenderJob& job : jobs.value()) {
            // Watching is about one viewpoint at a time: images only, the first path frame.
            if (job.kind != RenderJobKind::Image || job.frame > 0 ||
                (cameraName && job.camera != *cameraName && job.path != *cameraName)) {
                continue;
            }
            if (!job.path.empty() && !paths.count(job.path)) {
                Result<CameraPath> path = CameraPath::fromBlock(*session.model.findPath(job.path));
                if (!path) {
                    reportError(path.error().message);
                    return false;
                }
                paths.emplace(job.path, std::move(path.value()));
            }
            Result<std::pair<const ProjectModel*, SourceGraph*>> scenario =
                session.forScenario(job.scenario);
            if (!scenario) {
                reportError(scenario.error().message);
                ok = false;
                continue;
            }
            Result<TerrainLayers> layers =
                scenario->second->terrainLayers(*scenario->first, job.scenario);
            if (!layers) {
                reportError(layers.error().message);
                ok = false;
                continue;
            }
            Result<JobView> view =
                viewForJob(session.model, job, layers.value(), *scheduler, setup.value(), paths);
            if (!view) {
                reportError(view.error().message);
                ok = false;
                continue;
            }
            render::RenderSettings settings = setup.value().settings;
            settings.sunDirection = view.value().sun;
            settings.linearOutput = ImageWriter::isExr(job.output);
            Result<render::Image> image =
                renderer->render(layers.value(), *scheduler, view.value().camera, settings);
            if (!image) {
                reportError(view.value().what + ": " + image.error().message);
                ok = false;
                continue;
            }
            const Status written = writeRenderedImage(job.output, image.value());
            if (!written) {
                reportError(written.error().message);
                ok = false;
                continue;
            }
            ++images;
            std::printf("%s  %dx%d\n", job.output.string().c_str(), image->width, image->height);
        }
        if (images == 0 && ok) {
            reportError("nothing to render: no image of views '" + viewsName + "'" +
                        (cameraName ? " with camera '" + *cameraName + "'" : std::string()));
            return false;
        }
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
        std::printf("edit-to-image latency: %.2f s, %zu tiles recomputed, %zu cached\n", seconds,
                    scheduler->totals().misses - tilesBefore, scheduler->totals().tiles);
        std::fflush(stdout);
        return ok;
    };

    auto since = std::chrono::steady_clock::now();
    if (current.session) {
        status = renderAll(*current.session, since) ? 0 : 1;
        ++renders;
    }
    startWatching(current);
    std::printf("watching %zu files (Ctrl-C to stop)\n", watch.size());
    std::fflush(stdout);
    while (!stopWatching.load() && renders < exitAfter) {
        std::this_thread::sleep_for(std::chrono::milliseconds(intervalMs));
        const std::vector<std::filesystem::path> changed = watch.poll();
        if (changed.empty()) {
            continue;
        }
        since = std::chrono::steady_clock::now();
        for (const std::filesystem::path& file : changed) {
            std::printf("changed: %s\n", file.string().c_str());
        }
        std::fflush(stdout);
        Loaded next = load(projectFile, command);
        if (!next.session) {
            std::printf("the project has errors: keeping the last images\n");
            std::fflush(stdout);
            startWatching(next);
            status = 1;
            continue;
        }
        // Build the new graphs, keep the tiles of unchanged sources, then let the old
        // graphs go (retainOnly waits for running tasks of dropped sources).
        for (const Block& scenario : next.session->model.scenarios) {
            (void)next.session->forScenario(scenario.name);
        }
        std::unordered_set<std::uint64_t> live;
        if (next.session->graph) {
            live = next.session->graph->contentHashes();
        }
        for (const auto& [name, graph] : next.session->scenarioGraphs) {
            const std::unordered_set<std::uint64_t> hashes = graph.contentHashes();
            live.insert(hashes.begin(), hashes.end());
        }
        if (scheduler) {
            scheduler->retainOnly(live);
        }
        current = std::move(next);
        status = renderAll(*current.session, since) ? 0 : 1;
        ++renders;
        startWatching(current);
    }
    std::signal(SIGINT, SIG_DFL);
    std::signal(SIGTERM, SIG_DFL);
    return status;
}

}  // namespace sylva::app
