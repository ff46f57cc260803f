// ViewerSession: the state of one viewer run and every action on it — the project (held
// by the BatchRenderer), the shown scenario, the camera and navigation mode, the time
// and sun, the last frame and its statistics, the hot-reload watch — shared by the
// interactive loop (Viewer) and the script player (ScriptPlayer), so a script does
// exactly what keys do. Private to render/viewer.
//
// Frames render through BatchRenderer::sceneRenderer and ::scheduler (RenderSetup of the
// project's render block, the window's size); cameras of the project through
// JobView::forJob, so a shown camera equals the batch image of it. Data and project
// errors never end the session: they are kept in error() for the overlay, printed once,
// and the last good state stays.
#pragma once

#include <chrono>
#include <optional>
#include <string>
#include <vector>

#include "sylva/core/base/FileWatch.h"
#include "sylva/render/viewer/FrameBudget.h"
#include "sylva/render/viewer/Viewer.h"

namespace sylva::render {

// Two scenarios at once (core/image ImageComparison): the shown scenario left/first,
// `other` right/second.
enum class ComparisonMode { None, Swipe, Blend, SideBySide, Difference };

struct FrameReport {
    double milliseconds = 0;      // the whole frame: update, draw, read-back
    bool pending = false;         // wanted tiles still being produced
    std::size_t queuedTiles = 0;  // tasks queued in the scheduler
    std::size_t instancesDrawn = 0;
    int levelsDrawn = 0;
    int levelsWanted = 0;
};

class ViewerSession {
public:
    ViewerSession(BatchRenderer& batch, ViewerHost& host, const ViewerOptions& options);

    // Setup, renderer, scheduler, scenario and first camera; fails on an unknown scenario
    // or camera (the message names the choices) or when GL cannot render.
    Status start();

    // Size of the frames (the window's framebuffer, else the render setup's).
    void setFrameSize(int width, int height);

    Status goToCamera(const std::string& name);
    Status goToCamera(std::size_t index);  // the index-th camera block (keys 1..9)
    Status setScenario(const std::string& name);
    Status nextScenario();
    void setTime(double unixSeconds);
    void shiftTime(double seconds);  // from a midsummer solar noon when no time is set
    void setMode(NavigationMode mode);
    void cycleMode();
    // Moves in metres (fly: camera axes; walk and orbit: along the ground, up = height),
    // keeping the camera above the ground; turns in radians; drags the globe by pixels.
    void move(double forward, double right, double up);
    void turn(double yaw, double pitch);
    void orbit(double north, double east);
    void dragGlobe(double pixelsX, double pixelsY);
    void zoom(double steps);
    void changeQuality(int steps);
    void setQualityScale(double scale);  // vegetation quality factor, 0.1..10
    double qualityScale() const { return qualityScale_; }
    // Layers: "colour" (off: neutral grey terrain), "vegetation", "atmosphere".
    Status setLayer(const std::string& name, bool on);
    bool layerOn(const std::string& name) const;
    // Shows the current scenario against `other` (an error names unknown scenarios);
    // `amount` is the swipe split or blend amount in [0, 1].
    Status setComparison(ComparisonMode mode, const std::string& other, double amount);
    ComparisonMode comparisonMode() const { return comparison_; }
    const std::string& comparisonScenario() const { return otherScenario_; }
    double comparisonAmount() const { return comparisonAmount_; }
    const std::string& scenario() const { return scenario_; }
    std::vector<std::string> scenarioNames() const;
    std::vector<std::string> cameraNames() const;
    std::optional<double> time() const { return unixSeconds_; }
    void clearTime();
    // Travel speed (metres per second) at the current height above the ground.
    double speed() const;

    // Writes the camera into the project (ViewerHost::saveCamera), first placed on the
    // finest level's ground as a screenshot places it (walk: eye height over it; fly: at
    // least the clearance), waiting for the tiles under the camera.
    Status saveCamera(const std::string& name, const std::string& views);
    // Lat/lon/height and distance of the surface under framebuffer pixel (x, y) of the
    // last frame, as text for the overlay; "nothing" when the pixel shows the sky.
    std::string pick(double x, double y);

    // Renders one frame (interactive: ready tiles only; screenshots wait for all). A
    // failed frame keeps the last image, sets error() and returns the error.
    Status renderFrame(bool waitForTiles);
    // Whether something changed since the last frame or tiles are still arriving.
    // Also once after a still, complete view drawn below full quality by the budget: it
    // is redrawn at the window's resolution and full detail (then the viewer idles).
    bool needsFrame() const { return dirty_ || report_.pending || reduced_; }
    // Whether the view changed since the last frame (not only tiles arriving).
    bool changed() const { return dirty_; }
    NavigationMode mode() const { return mode_; }
    // Polls the watched files; on a change reloads the project (hot reload). Returns
    // whether anything changed.
    bool pollFiles();
    // Renders with every tile waited for and writes the image (PNG) atomically.
    Status screenshot(const std::filesystem::path& path);
    // Sleeps until a tile finished since the last frame or `seconds` pass (instead of
    // spinning); returns whether one did, i.e. whether a redraw can show something new.
    bool waitForTiles(double seconds);

    const Image& image() const { return image_; }
    const FrameReport& report() const { return report_; }
    const std::string& error() const { return error_; }
    // Status lines for the overlay: mode, scenario, time, height, speed, frame, tiles.
    std::vector<std::string> statusLines() const;
    std::size_t reloads() const { return reloads_; }
    std::size_t frames() const { return frames_; }
    // Seconds start() spent preparing (prepare()); 0 without a budget.
    double startupSeconds() const { return startupSeconds_; }
    const FrameBudget& budget() const { return budget_; }
    FILE* log() const { return options_.log; }

private:
    Status useScenario(const std::string& name);
    // The render settings of a frame: full detail (screenshots, refined still views), or
    // interactive at budget `level` (FrameBudget's ladder: vegetation, then resolution).
    RenderSettings frameSettings(bool full, int level) const;
    // Start-up, before the first interactive frame, with a budget: the scenario's plant
    // species built and uploaded, and one frame at the budget's coarsest level (its
    // programs, targets and tables made), so no frame of the loop pays them (issue 20's
    // bench: 278 ms of species upload and ~300 ms of first use inside its first frames).
    // Not a frame of the loop: no onFrame, no budget measurement; timed in startupSeconds_.
    void prepare();
    // One scenario's frame with the current camera and settings.
    Result<Image> renderScenario(const TerrainLayers& layers, const RenderSettings& settings);
    // The comparison of the two scenario frames, or the error.
    Result<Image> compose(Image first, Image second) const;
    void setCamera(const Camera& camera);  // keeps it above the ground, marks dirty
    // The ground under a point: without `wait` from the finest ring level whose tile is
    // ready (never blocks), with `wait` the finest level's for that height (as JobView).
    std::optional<double> groundHeight(double latitude, double longitude, double heightAboveGround,
                                       bool wait) const;
    // The height `camera` is placed at: walking, eye height over the surface stood on (the
    // terrain, or a mesh surface within a step of the current feet:
    // WalkerCollision::standingHeight); at least the clearance over the terrain otherwise;
    // nothing when the ground's tile failed.
    std::optional<double> placedHeight(const Camera& camera, bool wait) const;
    // Follows the ground under the standing camera (see placedHeight) without marking a
    // change: interactive frames as finer tiles arrive, screenshots at the finest level.
    void settleOnGround(bool wait);
    void watchFiles();
    void showError(const std::string& message);

    BatchRenderer& batch_;
    ViewerHost& host_;
    ViewerOptions options_;
    RenderSetup setup_;
    SceneRenderer* renderer_ = nullptr;
    Scheduler* scheduler_ = nullptr;
    std::string scenario_;
    TerrainLayers layers_;
    Camera camera_;
    NavigationMode mode_ = NavigationMode::Fly;
    std::optional<double> unixSeconds_;
    glm::dvec3 sun_{0, 0, 1};
    int width_ = 0;
    int height_ = 0;
    bool dirty_ = true;
    // The last frame refined a still view (full detail); it goes on refining until the view
    // changes, also while the tiles its full detail asked for arrive.
    bool refining_ = false;
    bool reduced_ = false;  // the last frame was drawn below full quality (budget level > 0)
    Image image_;
    std::vector<float> depth_;  // of the last frame (picking)
    double near_ = 1.0;
    FrameReport report_;
    FrameBudget budget_;
    // The shown scenario's meshes near the camera as the last frame drew them: what the
    // walker stands on and is stopped by.
    MeshCollision meshCollision_;
    std::string error_;
    FileWatch watch_;
    std::size_t reloads_ = 0;
    std::size_t frames_ = 0;
    double startupSeconds_ = 0;
    std::uint64_t finishedAtFrame_ = 0;  // Scheduler::finishedTasks() when the last frame began
    std::chrono::steady_clock::time_point lastFrameEnd_{};
    double qualityScale_ = 1.0;
    bool colourLayer_ = true;
    bool vegetationLayer_ = true;
    bool atmosphereLayer_ = true;
    ComparisonMode comparison_ = ComparisonMode::None;
    std::string otherScenario_;
    TerrainLayers otherLayers_;
    double comparisonAmount_ = 0.5;
};

}  // namespace sylva::render
