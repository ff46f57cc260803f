// `sylva render PROJECT [--views NAME] [--out DIR] [--size WxH] [--gl egl|osmesa|glfw] [-D name=value]`
// Renders every view of the project (or of one views block) and writes each image
// atomically. Exit code 0 only when every image was written.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

#include "CommandLine.h"
#include "Commands.h"
#include "ProjectSession.h"
#include "sylva/core/image/ImageWriter.h"
#include "sylva/core/scene/BlockReader.h"
#include "sylva/core/terrain/ElevationQuery.h"
#include "sylva/core/terrain/LevelVisibility.h"
#include "sylva/core/tiles/Scheduler.h"
#include "sylva/render/GlContext.h"
#include "sylva/render/SceneRenderer.h"

namespace sylva::app {
namespace {

struct Job {
    const Block* views = nullptr;
    const Block* camera = nullptr;
    std::string scenario;  // empty: the project's first scenario
    std::filesystem::path output;
};

std::string replaceAll(std::string text, const std::string& from, const std::string& to) {
    for (std::size_t at = text.find(from); at != std::string::npos; at = text.find(from, at + to.size())) {
        text.replace(at, from.size(), to);
    }
    return text;
}

// Checks that `folder` exists (creating it) and accepts files, before any rendering.
bool checkWritable(const std::filesystem::path& folder) {
    std::error_code error;
    std::filesystem::create_directories(folder, error);
    if (error) {
        reportError("cannot create output folder '" + folder.string() + "': " + error.message());
        return false;
    }
    const std::filesystem::path probe = folder / (".sylva-write-test-" + std::to_string(::getpid()));
    {
        std::ofstream stream(probe);
        if (!stream) {
            reportError("cannot write to output folder '" + folder.string() + "': permission denied or read-only");
            return false;
        }
    }
    std::filesystem::remove(probe, error);
    return true;
}

bool parseSize(const std::string& text, int& width, int& height) {
    int w = 0, h = 0;
    char x = 0, extra = 0;
    if (std::sscanf(text.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || (x != 'x' && x != 'X') || w < 1 ||
        h < 1 || w > 16384 || h > 16384) {
        return false;
    }
    width = w;
    height = h;
    return true;
}

}  // namespace

int runRender(const std::vector<std::string>& arguments) {
    const ParsedCommandLine command =
        parseCommandLine(arguments, {{"views"}, {"out"}, {"size"}, {"gl"}, {"cache-mb"}, {"help", false}});
    if (command.has("help")) {
        std::puts("usage: sylva render PROJECT [--views NAME] [--out DIR] [--size WxH] [--gl egl|osmesa|glfw] "
                  "[--cache-mb N] [-D name=value]");
        return 0;
    }
    if (!command.error.empty() || command.positional.size() != 1) {
        reportError(command.error.empty() ? "render needs exactly one project file (see 'sylva render --help')"
                                          : command.error);
        return 2;
    }
    int overrideWidth = 0, overrideHeight = 0;
    if (std::optional<std::string> size = command.get("size"); size && !parseSize(*size, overrideWidth, overrideHeight)) {
        reportError("--size expects WIDTHxHEIGHT within 1..16384, got '" + *size + "'");
        return 2;
    }
    std::size_t cacheMegabytes = 1024;
    if (std::optional<std::string> cache = command.get("cache-mb")) {
        const std::optional<std::size_t> parsed = parseCacheMegabytes(*cache);
        if (!parsed) {
            reportError("--cache-mb expects a tile cache budget in MiB within 16..1048576, got '" + *cache + "'");
            return 2;
        }
        cacheMegabytes = *parsed;
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

    std::optional<ProjectSession> session = ProjectSession::open(command.positional[0], command.defines);
    if (!session) {
        return 1;
    }
    const ProjectModel& model = session->model;

    // Expand views x scenarios x cameras into jobs before touching GL or the disk.
    std::vector<const Block*> viewBlocks;
    if (std::optional<std::string> name = command.get("views")) {
        const Block* views = model.findViews(*name);
        if (views == nullptr) {
            std::string known;
            for (const Block& block : model.views) {
                known += (known.empty() ? "" : ", ") + block.name;
            }
            reportError(model.file.string() + ": no views block named '" + *name + "'" +
                        (known.empty() ? "" : " (the project has: " + known + ")"));
            return 1;
        }
        viewBlocks.push_back(views);
    } else {
        for (const Block& block : model.views) {
            viewBlocks.push_back(&block);
        }
    }
    if (viewBlocks.empty()) {
        reportError(model.file.string() + ": the project has no views block: nothing to render");
        return 1;
    }
    const std::filesystem::path outputFolder = command.get("out").value_or("out");
    std::vector<Job> jobs;
    std::map<std::filesystem::path, const Job*> outputs;
    for (const Block* views : viewBlocks) {
        BlockReader reader(*views, SchemaRegistry::builtin().find("views"));
        std::vector<std::string> scenarios = reader.references("scenarios");
        if (scenarios.empty()) {
            scenarios.push_back(model.scenarios.empty() ? std::string() : model.scenarios.front().name);
        }
        const std::string pattern = reader.string("output", "{camera}.png");
        for (const std::string& scenario : scenarios) {
            for (const std::string& cameraName : reader.references("cameras")) {
                Job job;
                job.views = views;
                job.camera = model.findCamera(cameraName);
                job.scenario = scenario;
                job.output = outputFolder / replaceAll(replaceAll(pattern, "{camera}", cameraName), "{scenario}", scenario);
                if (job.camera == nullptr) {
                    reportError(reader.where("cameras") + "unknown camera '" + cameraName + "'");
                    return 1;
                }
                jobs.push_back(job);
            }
        }
    }
    for (const Job& job : jobs) {
        const std::filesystem::path normal = job.output.lexically_normal();
        if (outputs.count(normal) != 0) {
            reportError(job.views->location.toString() + ": views '" + job.views->name + "': two images would be written to '" +
                        normal.string() + "'; put {camera} and {scenario} into the output template");
            return 1;
        }
        outputs[normal] = &job;
    }
    for (const Job& job : jobs) {
        const std::filesystem::path folder = job.output.has_parent_path() ? job.output.parent_path() : ".";
        if (!checkWritable(folder)) {
            return 1;
        }
    }

    BlockReader renderBlock(model.render, SchemaRegistry::builtin().find("render"));
    render::RenderSettings settings;
    if (overrideWidth > 0) {
        settings.width = overrideWidth;
        settings.height = overrideHeight;
    } else if (const Value* resolution = renderBlock.value("resolution")) {
        const ValueList* list = resolution->get<ValueList>();
        if (list == nullptr || list->size() != 2 || !(*list)[0].get<Quantity>() || !(*list)[1].get<Quantity>()) {
            reportError(renderBlock.where("resolution") + "resolution must be [width, height]");
            return 1;
        }
        settings.width = static_cast<int>((*list)[0].get<Quantity>()->value);
        settings.height = static_cast<int>((*list)[1].get<Quantity>()->value);
        if (settings.width < 1 || settings.height < 1 || settings.width > 16384 || settings.height > 16384) {
            reportError(renderBlock.where("resolution") + "resolution must be within 1..16384 pixels");
            return 1;
        }
    }
    const GeoPosition sun = renderBlock.geo("sun").value_or(GeoPosition{0.4, 0.35, std::nullopt});
    settings.sunDirection = Ellipsoid::surfaceNormal(sun.latitude, sun.longitude);
    settings.atmosphere = renderBlock.boolean("atmosphere", true);
    settings.ocean = renderBlock.boolean("ocean", true);
    settings.exposure = renderBlock.optionalNumber("exposure").value_or(1.0);
    render::TerrainSettings terrainSettings;
    terrainSettings.maxLevel = static_cast<int>(renderBlock.optionalNumber("max_level").value_or(24));

    render::ContextOptions contextOptions;
    contextOptions.backend = backend;
    Result<std::unique_ptr<render::GlContext>> context = render::GlContext::create(contextOptions);
    if (!context) {
        reportError(context.error().message);
        return 1;
    }
    const render::ShaderLibrary library;
    Result<std::unique_ptr<render::SceneRenderer>> renderer = render::SceneRenderer::create(library, terrainSettings);
    if (!renderer) {
        reportError(renderer.error().message);
        return 1;
    }
    // Tiles come from the concurrent scheduler (one worker per core); every image
    // waits for all its levels (RenderSettings::waitForTiles), so output does not
    // depend on thread timing.
    SchedulerOptions schedulerOptions;
    schedulerOptions.format = TileFormat{terrainSettings.clipmapSize, 2};
    schedulerOptions.budgetBytes = cacheMegabytes << 20;
    Scheduler evaluator(schedulerOptions);

    int failures = 0;
    int degraded = 0;
    for (const Job& job : jobs) {
        const auto start = std::chrono::steady_clock::now();
        const std::size_t tilesBefore = evaluator.totals().misses;
        // Each scenario renders its own model (overrides applied); unchanged sources
        // keep their content hashes, so their tiles come from the shared cache.
        Result<std::pair<const ProjectModel*, SourceGraph*>> scenario = session->forScenario(job.scenario);
        if (!scenario) {
            reportError(scenario.error().message);
            ++failures;
            continue;
        }
        Result<TerrainLayers> layers = scenario->second->terrainLayers(*scenario->first, job.scenario);
        if (!layers) {
            reportError(layers.error().message);
            ++failures;
            continue;
        }
        const ElevationQuery query(*layers.value().elevation, evaluator);
        const Camera::TerrainHeight terrainHeight = [&](double latitude, double longitude) -> Result<double> {
            // The ground as the finest ring level under an eye-height camera draws it.
            BlockReader camera(*job.camera, SchemaRegistry::builtin().find("camera"));
            const double eye = camera.optionalNumber("eye_height").value_or(100.0);
            const double fov = camera.optionalNumber("fov").value_or(1.0);
            const LevelRange levels = LevelVisibility::visibleLevels(eye, eye, terrainSettings.maxTerrainHeight, fov,
                                                                     settings.height, terrainSettings.maxLevel);
            Result<double> height = query.groundHeight(latitude, longitude, levels.finest);
            if (height && settings.ocean) {
                return std::max(height.value(), 0.0);
            }
            return height;
        };
        Result<Camera> camera = Camera::fromBlock(*job.camera, terrainHeight);
        if (!camera) {
            reportError(camera.error().message);
            ++failures;
            continue;
        }
        Result<render::Image> image = renderer.value()->render(layers.value(), evaluator, camera.value(), settings);
        if (!image) {
            reportError(job.camera->location.toString() + ": camera '" + job.camera->name + "': " + image.error().message);
            ++failures;
            continue;
        }
        const Status written = ImageWriter::writeRgba8(job.output, image->width, image->height, image->pixels);
        if (!written) {
            reportError(written.error().message);
            ++failures;
            continue;
        }
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        const render::RenderStatistics& stats = renderer.value()->statistics();
        if (!stats.terrain.degraded.empty()) {
            // The image is written (coarser data is better than none), but the exit
            // status must say that data was missing.
            reportError(job.camera->location.toString() + ": camera '" + job.camera->name +
                        "': drawn with coarser terrain: " + stats.terrain.degraded);
            ++degraded;
        }
        std::printf("%s  %dx%d  %.2f s  (levels %d-%d, %llu triangles, %zu tiles)\n", job.output.string().c_str(),
                    image->width, image->height, seconds, stats.terrain.levels.coarsest, stats.terrain.levels.finest,
                    static_cast<unsigned long long>(stats.terrain.triangles), evaluator.totals().misses - tilesBefore);
        std::fflush(stdout);
    }
    if (failures > 0) {
        reportError(std::to_string(failures) + " of " + std::to_string(jobs.size()) + " images could not be rendered");
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
