// `sylva view PROJECT [--scenario S] [--camera C] [--size WxH] [--budget-ms N]
//                     [--script FILE] [--gl glfw|egl|osmesa] [--cache-mb N]
//                     [--disk-cache DIR | --no-disk-cache] [--disk-cache-mb N] [-D name=value]`
// The interactive viewer (docs/viewer.md): parses options, loads the script (a bad one is
// a located error before anything opens) and the project (diagnostics and exit codes as
// `render`), opens the window through render::BatchRenderer and hands over to
// render::Viewer. This file also implements the viewer's access to the project language
// (render never parses project text): reloading and writing camera blocks back
// (dsl::CameraBlockEditor).
#include <cstdio>
#include <optional>
#include <string>

#include "CommandLine.h"
#include "Commands.h"
#include "ProjectSession.h"
#include "sylva/core/scene/ViewerScript.h"
#include "sylva/dsl/CameraBlockEditor.h"
#include "sylva/render/batch/BatchRenderer.h"
#include "sylva/render/viewer/Viewer.h"

namespace sylva::app {
namespace {

const char* kUsage =
    "usage: sylva view PROJECT [--scenario NAME] [--camera NAME] [--size WxH] [--budget-ms N]\n"
    "                  [--script FILE] [--gl glfw|egl|osmesa] [--cache-mb N]\n"
    "                  [--disk-cache DIR | --no-disk-cache] [--disk-cache-mb N] [-D name=value]\n"
    "  Opens a window (GLFW, needs an X display such as Xvfb); --gl egl|osmesa runs a\n"
    "  --script headless. The disk tile cache is on by default, as for `sylva render`\n"
    "  (a project viewed or rendered before comes up from it). Keys and the script\n"
    "  language: docs/viewer.md.";

// The project language for the viewer: reload and camera write-back.
class CommandLineViewerHost final : public render::ViewerHost {
public:
    CommandLineViewerHost(std::filesystem::path project, const ParsedCommandLine& command)
        : project_(std::move(project)), command_(command) {}

    Result<std::vector<ProjectModel>> loadProject() override {
        dsl::LoadResult loaded = dsl::loadProject(project_, loadOptionsFor(command_));
        if (!loaded.files.empty()) {
            files_ = loaded.files;
        } else if (files_.empty()) {
            files_.push_back(project_);
        }
        printDiagnostics(loaded);
        if (loaded.hasErrors() || !loaded.model) {
            for (const dsl::Diagnostic& diagnostic : loaded.diagnostics) {
                if (diagnostic.severity == dsl::Severity::Error) {
                    return Error{diagnostic.location.toString() + ": error[" + diagnostic.code +
                                 "]: " + diagnostic.message};
                }
            }
            return Error{project_.string() + ": the project cannot be loaded"};
        }
        return scenarioModels(std::move(loaded));
    }

    std::vector<std::filesystem::path> projectFiles() const override { return files_; }

    Status saveCamera(const std::string& name, const Camera& camera,
                      const std::string& views) override {
        return dsl::CameraBlockEditor::save(project_, name, camera, views);
    }

private:
    std::filesystem::path project_;
    const ParsedCommandLine& command_;
    std::vector<std::filesystem::path> files_;
};

struct ViewRequest {
    std::filesystem::path project;
    render::BatchOptions batch;
    render::ViewerOptions viewer;
    bool sizeGiven = false;
};

// Fills `request` from the options (and loads the script); returns the exit code of a
// failure (2 usage, 1 a bad script) or 0.
int parseRequest(const ParsedCommandLine& command, ViewRequest& request) {
    if (!command.error.empty() || command.positional.size() != 1) {
        reportError(command.error.empty()
                        ? "view needs exactly one project file (see 'sylva view --help')"
                        : command.error);
        return 2;
    }
    request.project = command.positional[0];
    if (std::optional<std::string> size = command.get("size")) {
        if (!parseSize(*size, request.batch.width, request.batch.height)) {
            reportError("--size expects WIDTHxHEIGHT within 1..16384, got '" + *size + "'");
            return 2;
        }
        request.sizeGiven = true;
    }
    const Result<std::optional<int>> budget =
        wholeNumberOption(command, "budget-ms", 1, 100000, "expects milliseconds in 1..100000");
    const Result<std::optional<std::size_t>> cache = cacheMegabytesOption(command);
    Result<std::optional<render::GlBackend>> backend = glBackendOption(command);
    for (const std::string* error :
         {budget ? nullptr : &budget.error().message, cache ? nullptr : &cache.error().message,
          backend ? nullptr : &backend.error().message}) {
        if (error != nullptr) {
            reportError(*error);
            return 2;
        }
    }
    if (Status disk =
            diskCacheOptions(command, request.batch.diskCacheDisabled,
                             request.batch.diskCacheFolder, request.batch.diskCacheMegabytes);
        !disk) {
        reportError(disk.error().message);
        return 2;
    }
    // As `render`: tiles produced once (by a render, a farm or an earlier session) come
    // from the disk, so a view comes up in seconds instead of re-producing every tile.
    request.batch.diskCacheByDefault = true;
    request.viewer.budgetMilliseconds = budget.value().value_or(0);
    request.batch.cacheMegabytes = cache.value();
    request.batch.backend = backend.value().value_or(render::GlBackend::Glfw);
    request.batch.visibleWindow = request.batch.backend == render::GlBackend::Glfw;
    request.batch.windowTitle = "Sylva - " + request.project.filename().string();
    request.viewer.scenario = command.get("scenario").value_or("");
    request.viewer.camera = command.get("camera").value_or("");
    if (std::optional<std::string> script = command.get("script")) {
        Result<std::vector<ScriptCommand>> commands = ViewerScript::load(*script);
        if (!commands) {
            reportError(commands.error().message);
            return 1;
        }
        request.viewer.script = std::move(commands.value());
    } else if (!request.batch.visibleWindow) {
        reportError("--gl " + std::string(render::backendName(*request.batch.backend)) +
                    " has no window: give a --script to run headless");
        return 2;
    }
    request.viewer.closeAfterScript = !request.batch.visibleWindow;
    return 0;
}

}  // namespace

int runView(const std::vector<std::string>& arguments) {
    const ParsedCommandLine command = parseCommandLine(arguments, {{"scenario"},
                                                                   {"camera"},
                                                                   {"size"},
                                                                   {"budget-ms"},
                                                                   {"script"},
                                                                   {"gl"},
                                                                   {"cache-mb"},
                                                                   {"disk-cache"},
                                                                   {"disk-cache-mb"},
                                                                   {"no-disk-cache", false},
                                                                   {"help", false}});
    if (command.has("help")) {
        std::puts(kUsage);
        return 0;
    }
    ViewRequest request;
    if (int failed = parseRequest(command, request); failed != 0) {
        return failed;
    }
    CommandLineViewerHost host(request.project, command);
    Result<std::vector<ProjectModel>> models = host.loadProject();
    if (!models) {
        return 1;  // the diagnostics are printed
    }
    if (!request.sizeGiven) {
        // The window gets the render block's resolution.
        Result<render::RenderSetup> setup = render::RenderSetup::fromModel(models->front());
        if (!setup) {
            reportError(setup.error().message);
            return 1;
        }
        request.batch.width = setup->settings.width;
        request.batch.height = setup->settings.height;
    }
    render::BatchRenderer batch(request.batch);
    if (Status context = batch.createContext(); !context) {
        const std::string& reason = context.error().message;
        const bool hinted = reason.find("--gl") != std::string::npos;
        reportError("cannot open the viewer: " + reason +
                    (request.batch.visibleWindow && !hinted
                         ? " (a window needs an X display, e.g. `Xvfb :99 &` and DISPLAY=:99; "
                           "scripted runs work headless with --gl egl or osmesa)"
                         : ""));
        return 1;
    }
    if (Status set = batch.setProject(std::move(models.value())); !set) {
        reportError(set.error().message);
        return 1;
    }
    render::Viewer viewer(batch, host, std::move(request.viewer));
    if (Status ran = viewer.run(); !ran) {
        reportError(ran.error().message);
        return 1;
    }
    return 0;
}

}  // namespace sylva::app
