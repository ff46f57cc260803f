// Viewer: the interactive viewer of `sylva view` (docs/viewer.md): a window loop that
// renders a project's scenario through the BatchRenderer's SceneRenderer and Scheduler
// (so it draws exactly what `sylva render` draws, with waitForTiles = false for
// interactive frames), only while something changes — the camera, the time, the
// scenario, tiles still arriving, an edit — and sleeps in the window's event wait
// otherwise. It navigates (orbit, fly, walk above the CPU elevation query's ground,
// speed scaled by the height above the terrain), goes to the project's cameras
// (JobView::forJob, so the view equals the batch image of that camera), replays a
// ViewerScript, takes screenshots (rendered with every tile waited for, as a batch image
// is), saves cameras back into the project (through ViewerHost) and reloads the project
// and its data files when they change (hot reload: only sources whose content hash
// changed are recomputed; on errors the last good state stays and the error is shown).
//
// Without a window (--gl egl|osmesa) only a script can drive it. Thread: the one that
// owns the BatchRenderer's GL context. Errors of the project or data are shown and
// printed, never fatal; a script command that fails ends run() with its located error.
#pragma once

#include <cstdio>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "sylva/core/base/Result.h"
#include "sylva/core/model/ProjectModel.h"
#include "sylva/core/scene/Camera.h"
#include "sylva/core/scene/ViewerScript.h"
#include "sylva/core/sources/objects/WalkerCollision.h"
#include "sylva/render/batch/BatchRenderer.h"

namespace sylva::render {

// What the viewer needs from the project language (the app implements it with sylva_dsl;
// sylva_render never parses project text).
class ViewerHost {
public:
    virtual ~ViewerHost() = default;
    // Parses the project file again: one model per scenario, or the diagnostics as the
    // error's text.
    virtual Result<std::vector<ProjectModel>> loadProject() = 0;
    // The project's own files (the project and its imports) as of the last load.
    virtual std::vector<std::filesystem::path> projectFiles() const = 0;
    // Writes camera block `name` into the project file (and lists it in views block
    // `views` when not empty).
    virtual Status saveCamera(const std::string& name, const Camera& camera,
                              const std::string& views) = 0;
};

enum class NavigationMode { Orbit, Fly, Walk };

// One interactive frame as the viewer saw it (for benchmarks and tests); pointers valid
// only during the callback.
struct ViewerFrame {
    double milliseconds = 0;    // render call: update, draw, read-back
    bool pending = false;       // wanted tiles were still being produced
    bool moved = false;         // the view changed since the previous frame
    int budgetLevel = 0;        // FrameBudget level used (0 = full detail)
    double startupSeconds = 0;  // the session's preparation before its first frame
    // A still view's refinement at full detail and resolution: not chosen by the budget
    // (docs/viewer.md, "Frame budget"), drawn while the view stays still.
    bool refined = false;
    std::size_t instancesDrawn = 0;
    int levelsDrawn = 0;          // finest terrain ring level drawn
    int levelsWanted = 0;         // finest terrain ring level the view wants
    std::size_t queuedTiles = 0;  // tasks queued in the Scheduler after the frame
    // The frame's statistics (why it is pending: terrain waitingLevel, groundLevel, the
    // canopy, instance tiles, plant assets; the passes' times). Valid during the call.
    const RenderStatistics* statistics = nullptr;
    const Camera* camera = nullptr;
    const std::vector<float>* depth = nullptr;  // reversed-Z, rows top to bottom
    double near = 1.0;                          // distance = near / depth
    int width = 0;
    int height = 0;
};

struct ViewerOptions {
    std::string scenario;  // empty: the project's first
    std::string camera;    // empty: the first camera of the project, else a view from space
    // Frame budget in milliseconds for the vegetation level-of-detail controller; 0: none.
    double budgetMilliseconds = 0;
    std::vector<ScriptCommand> script;  // run first; the window stays open afterwards
    bool closeAfterScript = false;      // also without `quit` (headless runs)
    // Walk mode: eye height over the ground or the mesh surface stood on, the step climbed
    // and the distance kept from walls (core/sources/objects/WalkerCollision).
    WalkerBody walker;
    double tileTimeoutSeconds = 600;  // wait-tiles and screenshots give up after this
    FILE* log = stdout;               // reloads, saves, screenshots, script progress
    // Called after every interactive frame (not screenshots).
    std::function<void(const ViewerFrame&)> onFrame;
};

class Viewer {
public:
    // `batch` holds the project (setProject) and, for a window, a GLFW context created
    // with BatchOptions::visibleWindow.
    Viewer(BatchRenderer& batch, ViewerHost& host, ViewerOptions options);
    ~Viewer();
    Viewer(const Viewer&) = delete;
    Viewer& operator=(const Viewer&) = delete;

    // Runs the script, then (with a window) the interactive loop until the window closes,
    // Escape or `quit`. Fails with a script command's located error, or when the first
    // view cannot be set up (unknown scenario or camera).
    Status run();

private:
    class State;
    std::unique_ptr<State> state_;
};

}  // namespace sylva::render
