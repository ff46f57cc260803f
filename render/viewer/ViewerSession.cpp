#include "ViewerSession.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <thread>

#include "sylva/core/geo/SolarPosition.h"
#include "sylva/core/image/ImageComparison.h"
#include "sylva/core/scene/CameraNavigation.h"
#include "sylva/core/terrain/ElevationQuery.h"
#include "sylva/core/terrain/LevelVisibility.h"
#include "sylva/render/batch/ImageOutput.h"
#include "sylva/render/batch/JobView.h"

namespace sylva::render {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegrees = 180.0 / kPi;
// 2024-06-21T12:00:00Z: the time keys start from midsummer noon when no time is set.
constexpr double kMidsummerNoonUtc = 1718971200.0;
// Clearance kept above the ground when flying or orbiting, metres.
constexpr double kFlyClearance = 1.0;
// Pixels between the two halves of a side-by-side comparison.
constexpr int kSideBySideGap = 4;
// A still view with work pending (plant assets, tiles) is redrawn at least this often.
constexpr double kStillRedrawSeconds = 0.5;
// Texels per side of each shadow cascade in interactive frames (at most).
constexpr int kInteractiveShadowResolution = 1024;
// Out-of-date shadow cascades redrawn per interactive frame (ShadowSettings::maximumRedraws).
constexpr int kInteractiveShadowRedraws = 2;

// What the frame budget counts as the vegetation's primitives.
std::size_t primitivesOf(const RenderStatistics& statistics) {
    return statistics.vegetation.ellipsoids + statistics.vegetation.lines +
           statistics.vegetation.meshInstances + statistics.vegetation.billboardInstances;
}

const char* modeName(NavigationMode mode) {
    switch (mode) {
        case NavigationMode::Orbit:
            return "orbit";
        case NavigationMode::Fly:
            return "fly";
        case NavigationMode::Walk:
            return "walk";
    }
    return "?";
}

// Resident memory in MiB (Linux /proc/self/statm), 0 when unknown.
double residentMegabytes() {
    std::ifstream statm("/proc/self/statm");
    double pages = 0, resident = 0;
    if (!(statm >> pages >> resident)) {
        return 0;
    }
    return resident * 4096.0 / (1024.0 * 1024.0);
}

}  // namespace

ViewerSession::ViewerSession(BatchRenderer& batch, ViewerHost& host, const ViewerOptions& options)
    : batch_(batch), host_(host), options_(options), budget_(options.budgetMilliseconds) {}

Status ViewerSession::start() {
    Result<RenderSetup> setup = batch_.setup();
    if (!setup) {
        return setup.error();
    }
    setup_ = setup.value();
    width_ = setup_.settings.width;
    height_ = setup_.settings.height;
    sun_ = setup_.defaultSun;
    Result<SceneRenderer*> renderer = batch_.sceneRenderer(setup_);
    if (!renderer) {
        return renderer.error();
    }
    renderer_ = renderer.value();
    scheduler_ = &batch_.scheduler(setup_);
    const std::string scenario =
        options_.scenario.empty() ? batch_.project().defaultModel().scenario : options_.scenario;
    if (Status used = useScenario(scenario); !used) {
        return used;
    }
    const ProjectModel& model = batch_.project().defaultModel();
    if (!options_.camera.empty()) {
        if (Status moved = goToCamera(options_.camera); !moved) {
            return moved;
        }
    } else if (!model.cameras.empty()) {
        if (Status moved = goToCamera(std::size_t{0}); !moved) {
            return moved;
        }
    } else {
        // No camera in the project: the globe from 12,000 km over 0°, 0°.
        Camera camera;
        camera.verticalFov = 60.0 / kDegrees;
        camera.geodetic = {0.0, 0.0, 1.2e7};
        camera.position = Ellipsoid::toEcef(camera.geodetic);
        camera.axes = Camera::axesFromAngles(camera.geodetic, 0.0, -kPi / 2 + 1e-3, 0.0);
        camera_ = camera;
        mode_ = NavigationMode::Orbit;
    }
    watchFiles();
    if (options_.budgetMilliseconds > 0) {
        prepare();
    }
    return {};
}

void ViewerSession::prepare() {
    const auto start = std::chrono::steady_clock::now();
    // A species that fails to build is reported by the frames, as without preparing.
    if (Status species = renderer_->prepareSpecies(layers_); !species) {
        showError(species.error().message);
    }
    // The first frame at the coarsest level, its cost the budget's first measurement
    // (the loop's first frame then starts from a model, not from full detail: drawn at
    // level 0 it was the longest frame of the bench's flight, ~1 s).
    budget_.startAt(FrameBudget::kLevels - 1);
    RenderSettings settings = frameSettings(false, budget_.level());
    settings.waitForTiles = false;
    const auto frameStart = std::chrono::steady_clock::now();
    if (Result<Image> image = renderScenario(layers_, settings); !image) {
        showError(image.error().message);
    } else {
        const RenderStatistics& statistics = renderer_->statistics();
        FrameMeasurement measurement;
        measurement.frameMilliseconds =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - frameStart)
                .count();
        measurement.vegetationMilliseconds = statistics.vegetationPassSeconds * 1000.0;
        measurement.primitives = primitivesOf(statistics);
        budget_.record(measurement);
    }
    startupSeconds_ =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::fprintf(options_.log, "prepared in %.2f s (plant species, first frame)\n",
                 startupSeconds_);
    std::fflush(options_.log);
}

void ViewerSession::setFrameSize(int width, int height) {
    if (width > 0 && height > 0 && (width != width_ || height != height_)) {
        width_ = width;
        height_ = height;
        dirty_ = true;
    }
}

Status ViewerSession::useScenario(const std::string& name) {
    Result<TerrainLayers> layers = batch_.project().terrainLayers(name);
    if (!layers) {
        return layers.error();
    }
    layers_ = layers.value();
    scenario_ = name;
    dirty_ = true;
    return {};
}

Status ViewerSession::goToCamera(const std::string& name) {
    const ProjectModel& model = batch_.project().defaultModel();
    if (model.findCamera(name) == nullptr) {
        std::string names;
        for (const Block& block : model.cameras) {
            names += (names.empty() ? "" : ", ") + block.name;
        }
        return Error{"unknown camera '" + name + "' (cameras: " + (names.empty() ? "none" : names) +
                     ")"};
    }
    RenderJob job;
    job.camera = name;
    job.scenario = scenario_;
    Result<JobView> view = JobView::forJob(model, job, layers_, *scheduler_, setup_, nullptr);
    if (!view) {
        return view.error();
    }
    camera_ = view->camera;
    dirty_ = true;
    if (mode_ == NavigationMode::Walk) {
        mode_ = NavigationMode::Fly;  // a project camera keeps its height until W is chosen
    }
    return {};
}

Status ViewerSession::goToCamera(std::size_t index) {
    const ProjectModel& model = batch_.project().defaultModel();
    if (index >= model.cameras.size()) {
        return Error{"the project has " + std::to_string(model.cameras.size()) +
                     " cameras, no camera " + std::to_string(index + 1)};
    }
    return goToCamera(model.cameras[index].name);
}

Status ViewerSession::setScenario(const std::string& name) {
    return useScenario(name);
}

Status ViewerSession::nextScenario() {
    const std::vector<ProjectModel>& models = batch_.project().models();
    std::size_t current = 0;
    for (std::size_t i = 0; i < models.size(); ++i) {
        if (models[i].scenario == scenario_) {
            current = i;
        }
    }
    return useScenario(models[(current + 1) % models.size()].scenario);
}

void ViewerSession::setTime(double unixSeconds) {
    unixSeconds_ = unixSeconds;
    const SunPosition sun = SolarPosition::at(unixSeconds);
    sun_ = Ellipsoid::surfaceNormal(sun.subsolarLatitude, sun.subsolarLongitude);
    dirty_ = true;
}

void ViewerSession::shiftTime(double seconds) {
    const double start =
        unixSeconds_.value_or(kMidsummerNoonUtc - camera_.geodetic.longitude / (2 * kPi) * 86400.0);
    setTime(start + seconds);
}

void ViewerSession::setMode(NavigationMode mode) {
    mode_ = mode;
    setCamera(camera_);  // walk: down to eye height
}

void ViewerSession::cycleMode() {
    setMode(mode_ == NavigationMode::Orbit ? NavigationMode::Fly
            : mode_ == NavigationMode::Fly ? NavigationMode::Walk
                                           : NavigationMode::Orbit);
}

std::optional<double> ViewerSession::groundHeight(double latitude, double longitude,
                                                  double heightAboveGround, bool wait) const {
    // The ground as the finest ring level drawn at this height shows it (as JobView). A
    // move never waits for it: the finest level whose tile is ready (the finer ones are
    // requested), else the ground under the last frame (as SceneRenderer's frames do).
    const double height = std::max(heightAboveGround, 0.5);
    const LevelRange levels =
        LevelVisibility::visibleLevels(height, height, setup_.terrain.maxTerrainHeight,
                                       camera_.verticalFov, height_, setup_.terrain.maxLevel);
    const ElevationQuery query(*layers_.elevation, *scheduler_);
    const auto clamped = [&](double ground) {
        return setup_.settings.ocean ? std::max(ground, 0.0) : ground;
    };
    // No finer than the finest level resident (every coarser one brought up too), so the
    // renderer can draw from the level the camera stands on (its ground is below the eye)
    // and the walker climbs with the levels as they arrive. Not the level last drawn from
    // (textureLevel): that is lowered to a level whose ground is below the camera, so a
    // walker held on it stood under every finer level on a hill and never refined.
    const int resident = renderer_->statistics().terrain.residentLevel;
    const int finest =
        frames_ > 0 && resident >= 0 ? std::min(levels.finest, resident) : levels.finest;
    for (int level = finest; level >= 0 && !wait; --level) {
        Result<std::optional<double>> ground =
            query.readyGroundHeight(latitude, longitude, level, level);
        if (!ground) {
            return std::nullopt;
        }
        if (ground.value()) {
            return clamped(*ground.value());
        }
    }
    if (!wait && frames_ > 0) {
        return renderer_->statistics().groundHeight;  // the last frame's
    }
    Result<double> ground = query.groundHeight(latitude, longitude, wait ? levels.finest : 0);
    if (!ground) {
        return std::nullopt;
    }
    return clamped(ground.value());
}

std::optional<double> ViewerSession::placedHeight(const Camera& camera, bool wait) const {
    const double above = std::max(camera_.geodetic.height - camera.geodetic.height, 0.0) +
                         std::max(renderer_->statistics().heightAboveTerrain, 1.0);
    const std::optional<double> ground =
        groundHeight(camera.geodetic.latitude, camera.geodetic.longitude, above, wait);
    if (!ground) {
        return std::nullopt;
    }
    if (mode_ == NavigationMode::Walk) {
        // The feet are the current camera's: a walker steps onto what is within a step of
        // them, and one arriving from a flight lands on the highest surface below.
        const WalkerBody& body = options_.walker;
        return WalkerCollision::standingHeight(
                   meshCollision_, camera.geodetic.latitude, camera.geodetic.longitude,
                   camera_.geodetic.height - body.eyeHeight, *ground, body) +
               body.eyeHeight;
    }
    return std::max(camera.geodetic.height, *ground + kFlyClearance);
}

void ViewerSession::settleOnGround(bool wait) {
    // The ground under a standing camera refines as finer tiles arrive (or, for a
    // screenshot, is the finest level's at once): follow it without counting a move.
    const std::optional<double> height = placedHeight(camera_, wait);
    if (height && std::abs(*height - camera_.geodetic.height) > 1e-4) {
        camera_ = CameraNavigation::atHeight(camera_, *height);
    }
}

void ViewerSession::setCamera(const Camera& camera) {
    const std::optional<double> height = placedHeight(camera, false);
    if (!height) {
        showError("no ground height under the camera (a tile failed): not moved");
        return;
    }
    camera_ = std::abs(*height - camera.geodetic.height) > 0.0
                  ? CameraNavigation::atHeight(camera, *height)
                  : camera;
    dirty_ = true;
}

double ViewerSession::speed() const {
    if (mode_ == NavigationMode::Walk) {
        return CameraNavigation::speedFor(0.0);
    }
    return CameraNavigation::speedFor(std::max(renderer_->statistics().heightAboveTerrain, 0.0));
}

void ViewerSession::move(double forward, double right, double up) {
    if (mode_ == NavigationMode::Fly) {
        setCamera(CameraNavigation::fly(camera_, forward, right, up));
        return;
    }
    Camera moved = CameraNavigation::walk(camera_, forward, right);
    if (mode_ == NavigationMode::Orbit) {
        moved = CameraNavigation::atHeight(moved, moved.geodetic.height + up);
    } else {
        moved = WalkerCollision::step(meshCollision_, camera_, moved, options_.walker);
    }
    setCamera(moved);
}

void ViewerSession::turn(double yaw, double pitch) {
    camera_ = CameraNavigation::turn(camera_, yaw, pitch);
    dirty_ = true;
}

void ViewerSession::orbit(double north, double east) {
    setCamera(CameraNavigation::orbit(camera_, north, east));
}

void ViewerSession::dragGlobe(double pixelsX, double pixelsY) {
    // The ground under the view moves with the cursor: one pixel covers about
    // height × pixel angle metres, i.e. that over the radius in radians.
    const double pixelAngle = 2.0 * std::tan(camera_.verticalFov / 2) / std::max(height_, 1);
    const double radians = std::max(renderer_->statistics().heightAboveTerrain, 1.0) * pixelAngle /
                           Ellipsoid::kMeanRadius;
    const CameraAngles angles = CameraNavigation::anglesOf(camera_);
    const double c = std::cos(angles.heading), s = std::sin(angles.heading);
    // Screen right is (cos h, −sin h) in (east, north); screen up is (sin h, cos h).
    const double east = (-pixelsX * c + pixelsY * s) * radians;
    const double north = (pixelsX * s + pixelsY * c) * radians;
    orbit(north, east / std::max(std::cos(camera_.geodetic.latitude), 0.01));
}

void ViewerSession::zoom(double steps) {
    const double above = std::max(renderer_->statistics().heightAboveTerrain, 1.0);
    const double change = above * (std::pow(0.85, steps) - 1.0);
    setCamera(CameraNavigation::atHeight(camera_, camera_.geodetic.height + change));
}

void ViewerSession::changeQuality(int steps) {
    qualityScale_ = std::clamp(qualityScale_ * std::pow(1.5, steps), 0.1, 10.0);
    dirty_ = true;
}

void ViewerSession::setQualityScale(double scale) {
    qualityScale_ = std::clamp(scale, 0.1, 10.0);
    dirty_ = true;
}

Status ViewerSession::setLayer(const std::string& name, bool on) {
    bool* layer = name == "colour"       ? &colourLayer_
                  : name == "vegetation" ? &vegetationLayer_
                  : name == "atmosphere" ? &atmosphereLayer_
                                         : nullptr;
    if (layer == nullptr) {
        return Error{"unknown layer '" + name + "' (layers: colour, vegetation, atmosphere)"};
    }
    *layer = on;
    dirty_ = true;
    return {};
}

bool ViewerSession::layerOn(const std::string& name) const {
    return name == "colour"       ? colourLayer_
           : name == "vegetation" ? vegetationLayer_
           : name == "atmosphere" ? atmosphereLayer_
                                  : false;
}

Status ViewerSession::setComparison(ComparisonMode mode, const std::string& other, double amount) {
    if (mode != ComparisonMode::None) {
        Result<TerrainLayers> layers = batch_.project().terrainLayers(other);
        if (!layers) {
            return layers.error();
        }
        otherLayers_ = layers.value();
        otherScenario_ = other;
    }
    comparison_ = mode;
    comparisonAmount_ = std::clamp(amount, 0.0, 1.0);
    dirty_ = true;
    return {};
}

std::vector<std::string> ViewerSession::scenarioNames() const {
    std::vector<std::string> names;
    for (const ProjectModel& model : batch_.project().models()) {
        names.push_back(model.scenario);
    }
    return names;
}

std::vector<std::string> ViewerSession::cameraNames() const {
    std::vector<std::string> names;
    for (const Block& block : batch_.project().defaultModel().cameras) {
        names.push_back(block.name);
    }
    return names;
}

void ViewerSession::clearTime() {
    unixSeconds_.reset();
    sun_ = setup_.defaultSun;
    dirty_ = true;
}

void ViewerSession::showError(const std::string& message) {
    if (message != error_) {
        std::fprintf(stderr, "sylva view: %s\n", message.c_str());
    }
    error_ = message;
}

Result<Image> ViewerSession::renderScenario(const TerrainLayers& layers,
                                            const RenderSettings& settings) {
    TerrainLayers shown = layers;
    if (!colourLayer_) {
        shown.color = nullptr;  // neutral grey
    }
    if (!vegetationLayer_) {
        shown.plants.clear();
    }
    return renderer_->render(shown, *scheduler_, camera_, settings);
}

Result<Image> ViewerSession::compose(Image first, Image second) const {
    auto rgba = [](Image& image) {
        RgbaImage out;
        out.width = image.width;
        out.height = image.height;
        out.pixels = std::move(image.pixels);
        return out;
    };
    const RgbaImage left = rgba(first);
    const RgbaImage right = rgba(second);
    Result<RgbaImage> composed = Error{"no comparison"};
    switch (comparison_) {
        case ComparisonMode::Swipe:
            composed = ImageComparison::swipe(left, right, comparisonAmount_);
            break;
        case ComparisonMode::Blend:
            composed = ImageComparison::blend(left, right, comparisonAmount_);
            break;
        case ComparisonMode::SideBySide:
            composed = ImageComparison::sideBySide(left, right, kSideBySideGap);
            break;
        case ComparisonMode::Difference:
            composed = ImageComparison::difference(left, right);
            break;
        case ComparisonMode::None:
            break;
    }
    if (!composed) {
        return composed.error();
    }
    Image out;
    out.width = composed->width;
    out.height = composed->height;
    out.pixels = std::move(composed->pixels);
    return out;
}

RenderSettings ViewerSession::frameSettings(bool full, int level) const {
    RenderSettings settings = setup_.settings;
    // Interactive frames past the vegetation's coarsest budget level draw fewer pixels
    // (FrameBudget::renderScale); the window enlarges them. Screenshots: the window's.
    const double scale = full ? 1.0 : FrameBudget::scaleOf(level);
    const int width = std::max(int(std::lround(width_ * scale)), 1);
    settings.width = width;
    settings.height = std::max(int(std::lround(height_ * scale)), 1);
    settings.levelRows = height_;
    if (comparison_ == ComparisonMode::SideBySide) {
        settings.width = std::max((width - kSideBySideGap) / 2, 1);
    }
    settings.sunDirection = sun_;
    settings.atmosphere = setup_.settings.atmosphere && atmosphereLayer_;
    VegetationSettings vegetation = settings.vegetation;
    vegetation.quality *= qualityScale_;
    // Screenshots are full detail (as a batch image); interactive frames fit the budget.
    settings.vegetation = full ? vegetation : FrameBudget::settingsAt(vegetation, level);
    if (!full) {
        // The shadow cascades were half of an interactive frame on llvmpipe (issue 20's
        // trace: ~300 of ~600 ms at 320x180 with five 2048² depth passes); a quarter of
        // the texels while interacting, the project's resolution in screenshots.
        settings.shadows.resolution =
            std::min(settings.shadows.resolution, kInteractiveShadowResolution);
        // And at most two out-of-date cascades redrawn a frame (the finest, then the one
        // kept longest): as plant tiles arrived during a walk every cascade was redrawn,
        // 106-177 ms of 230-380 ms frames at the coarsest budget level (issue 20's bench).
        settings.shadows.maximumRedraws = kInteractiveShadowRedraws;
        // With a budget the vegetation cannot meet any more (its coarsest level), the
        // screen-space ambient occlusion goes too: at 1280x720 on llvmpipe it was the
        // largest pass of a frame (1.1-4.3 s of 2.7-6 s at load 8-11, issue 20's trace).
        if (options_.budgetMilliseconds > 0 && level >= FrameBudget::kVegetationLevels - 1) {
            settings.ambientOcclusion.enabled = false;
        }
    }
    return settings;
}

Status ViewerSession::renderFrame(bool waitForTiles) {
    settleOnGround(waitForTiles);
    // A still view whose tiles were all drawn by the last frame is refined: drawn at full
    // detail and resolution (not measured for the budget) until it changes again. Full
    // detail asks for tiles of its own (finer plants, a larger shadow map's casters); a
    // refining view that has to wait for them stays refining — dropping back to the
    // budget's level until they came, then refining again, was a quality reversal a
    // still view must not show (issue 20's `quality_oscillations`).
    const bool refine = !waitForTiles && !dirty_ && (!report_.pending || refining_) &&
                        options_.budgetMilliseconds > 0 && frames_ > 0;
    refining_ = refine;
    const bool full = waitForTiles || refine;
    RenderSettings settings = frameSettings(full, budget_.level());
    settings.waitForTiles = waitForTiles;
    const bool moved = dirty_;
    reduced_ = !full && budget_.level() > 0;
    finishedAtFrame_ = scheduler_->finishedTasks();
    const auto start = std::chrono::steady_clock::now();
    Result<Image> image = renderScenario(layers_, settings);
    if (image) {
        // Before a comparison's second scenario updates the mesh renderer.
        meshCollision_.setTiles(layers_.meshes.empty()
                                    ? std::vector<std::shared_ptr<const MeshTile>>{}
                                    : renderer_->meshes().shownTiles());
    }
    RenderStatistics statistics = renderer_->statistics();
    bool pending = statistics.pending;
    if (image && comparison_ != ComparisonMode::None) {
        Result<Image> second = renderScenario(otherLayers_, settings);
        const RenderStatistics& other = renderer_->statistics();
        pending = pending || other.pending;
        statistics.vegetationPassSeconds += other.vegetationPassSeconds;
        image = second ? compose(std::move(image.value()), std::move(second.value()))
                       : Result<Image>(second.error());
    }
    const double milliseconds =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    dirty_ = false;
    ++frames_;
    lastFrameEnd_ = std::chrono::steady_clock::now();
    if (!image) {
        report_.pending = false;
        showError(image.error().message);
        return image.error();
    }
    if (error_.rfind("project:", 0) != 0) {
        error_.clear();  // a project error stays until the project loads again
    }
    image_ = std::move(image.value());
    depth_.clear();  // read back only when needed (picking, frame callbacks)
    near_ = renderer_->near();
    report_.milliseconds = milliseconds;
    report_.levelsDrawn = statistics.terrain.textureLevel;  // the finest level resident
    report_.levelsWanted = statistics.terrain.wanted.finest;
    report_.queuedTiles = scheduler_->queuedTasks();
    report_.instancesDrawn = statistics.vegetation.drawnInstances;
    if (!waitForTiles && !pending) {
        // The frame made a finer level resident: the walker moves onto its ground in the
        // next frame (settleOnGround), so the view is not settled yet.
        const std::optional<double> placed = placedHeight(camera_, false);
        pending = placed && std::abs(*placed - camera_.geodetic.height) > 1e-4;
    }
    report_.pending = pending;
    FrameMeasurement measurement;
    measurement.frameMilliseconds = milliseconds;
    measurement.vegetationMilliseconds = statistics.vegetationPassSeconds * 1000.0;
    measurement.primitives = primitivesOf(statistics);
    measurement.cameraMoved = moved;
    if (!waitForTiles) {
        const int level = refine ? 0 : budget_.level();
        if (!refine) {
            budget_.record(measurement);
        }
        if (options_.onFrame) {
            ViewerFrame frame;
            frame.milliseconds = milliseconds;
            frame.pending = report_.pending;
            frame.moved = moved;
            frame.budgetLevel = level;
            frame.startupSeconds = startupSeconds_;
            frame.refined = refine;
            frame.instancesDrawn = report_.instancesDrawn;
            frame.levelsDrawn = report_.levelsDrawn;
            frame.levelsWanted = report_.levelsWanted;
            frame.queuedTiles = report_.queuedTiles;
            frame.statistics = &statistics;
            frame.camera = &camera_;
            depth_ = renderer_->depth();
            frame.depth = &depth_;
            frame.near = near_;
            frame.width = image_.width;
            frame.height = image_.height;
            options_.onFrame(frame);
        }
    }
    return {};
}

bool ViewerSession::waitForTiles(double seconds) {
    // A still view is redrawn when a tile finished since the last frame began, but not
    // sooner after the last frame than that frame took: while only tiles arrive the
    // render thread (and llvmpipe's threads) take at most about half the CPU, the rest
    // is the workers'. Redrawing each 50 ms starved them (issue 20: ~2 tiles/s while a
    // still 320x180 frame took 0.6 s). At the latest every kStillRedrawSeconds, for the
    // plant assets built outside the Scheduler.
    using Clock = std::chrono::steady_clock;
    const auto end = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                        std::chrono::duration<double>(seconds));
    const auto earliest =
        lastFrameEnd_ + std::chrono::duration_cast<Clock::duration>(
                            std::chrono::duration<double, std::milli>(report_.milliseconds));
    const auto latest = lastFrameEnd_ + std::chrono::duration_cast<Clock::duration>(
                                            std::chrono::duration<double>(kStillRedrawSeconds));
    while (true) {
        const auto now = Clock::now();
        if (now >= latest || (now >= earliest && scheduler_->finishedTasks() != finishedAtFrame_)) {
            return true;
        }
        if (now >= end) {
            return false;
        }
        const auto step =
            std::min({end, latest, std::max(earliest, now + std::chrono::milliseconds(1))}) - now;
        if (now < earliest) {
            std::this_thread::sleep_for(step);
        } else {
            scheduler_->waitForProgress(
                std::chrono::duration_cast<std::chrono::milliseconds>(step) +
                std::chrono::milliseconds(1));
        }
    }
}

void ViewerSession::watchFiles() {
    watch_.clear();
    for (const std::filesystem::path& file : host_.projectFiles()) {
        watch_.watch(file);
    }
    for (const std::filesystem::path& file : batch_.project().files()) {
        watch_.watch(file);
    }
}

bool ViewerSession::pollFiles() {
    const std::vector<std::filesystem::path> changed = watch_.poll();
    if (changed.empty()) {
        return false;
    }
    for (const std::filesystem::path& file : changed) {
        std::fprintf(options_.log, "changed: %s\n", file.string().c_str());
    }
    dirty_ = true;
    Result<std::vector<ProjectModel>> models = host_.loadProject();
    Status set = models ? batch_.setProject(std::move(models.value())) : Status(models.error());
    if (!set) {
        // The previous project and its graphs stay; the error is shown until a good load.
        showError("project: " + set.error().message);
        std::fprintf(options_.log, "the project has errors: keeping the last good state\n");
        std::fflush(options_.log);
        return true;
    }
    error_.clear();
    ++reloads_;
    // The render block may have changed (sun, exposure, atmosphere); the frame size stays.
    if (Result<RenderSetup> setup = batch_.setup(); setup) {
        setup_ = setup.value();
        if (!unixSeconds_) {
            sun_ = setup_.defaultSun;
        }
    } else {
        showError(setup.error().message);
    }
    const std::string scenario = scenario_;
    if (Status used = useScenario(scenario); !used) {
        showError(used.error().message + "; showing the first scenario");
        (void)useScenario(batch_.project().defaultModel().scenario);
    }
    if (comparison_ != ComparisonMode::None) {
        if (Status compared = setComparison(comparison_, otherScenario_, comparisonAmount_);
            !compared) {
            showError(compared.error().message + "; comparison off");
            comparison_ = ComparisonMode::None;
        }
    }
    watchFiles();
    std::fprintf(options_.log, "reloaded the project (%zu tiles cached are kept)\n",
                 scheduler_->totals().tiles);
    std::fflush(options_.log);
    return true;
}

Status ViewerSession::screenshot(const std::filesystem::path& path) {
    if (Status rendered = renderFrame(true); !rendered) {
        return rendered;
    }
    Image copy = image_;
    if (Status written = ImageOutput::write(path, copy); !written) {
        return written;
    }
    std::fprintf(options_.log, "screenshot: %s  %dx%d\n", path.string().c_str(), copy.width,
                 copy.height);
    std::fflush(options_.log);
    return {};
}

Status ViewerSession::saveCamera(const std::string& name, const std::string& views) {
    // Interactive frames stand the camera on the finest ground ready so far; a walker saved
    // before the fine tiles arrived stood on a coarse level's ground (at Olinda's coast,
    // the sea's: 60 m under the hill it was on), which the batch rejects as under the
    // terrain. The saved camera is placed as a screenshot places it: on the finest
    // level's ground, waited for (only the tiles under the camera).
    const double before = camera_.geodetic.height;
    settleOnGround(true);
    dirty_ = dirty_ || camera_.geodetic.height != before;
    if (Status saved = host_.saveCamera(name, camera_, views); !saved) {
        showError(saved.error().message);
        return saved;
    }
    std::fprintf(options_.log, "saved camera '%s'\n", name.c_str());
    std::fflush(options_.log);
    return {};
}

std::string ViewerSession::pick(double x, double y) {
    // Window pixels to the last frame's (smaller while the budget lowers the resolution).
    const int px = static_cast<int>(x * image_.width / std::max(width_, 1));
    const int py = static_cast<int>(y * image_.height / std::max(height_, 1));
    if (depth_.empty()) {
        depth_ = renderer_->depth();  // the G-buffer still holds the last frame
    }
    if (px < 0 || py < 0 || px >= image_.width || py >= image_.height ||
        depth_.size() != static_cast<std::size_t>(image_.width) * image_.height) {
        return "nothing";
    }
    const float depth = depth_[static_cast<std::size_t>(py) * image_.width + px];
    if (depth <= 0.0f) {
        return "nothing (sky)";
    }
    // Reversed-Z with an infinite far plane: depth = near / view distance along -z.
    const double along = near_ / depth;
    const double tangent = std::tan(camera_.verticalFov / 2);
    const double aspect = double(image_.width) / image_.height;
    const double viewX = (2.0 * (px + 0.5) / image_.width - 1.0) * tangent * aspect;
    const double viewY = (1.0 - 2.0 * (py + 0.5) / image_.height) * tangent;
    const glm::dvec3 point =
        camera_.position + camera_.axes * glm::dvec3(viewX, viewY, -1.0) * along;
    const Geodetic at = Ellipsoid::toGeodetic(point);
    char text[160];
    std::snprintf(text, sizeof text, "picked %.6f deg, %.6f deg, %.1f m; distance %.1f m",
                  at.latitude * kDegrees, at.longitude * kDegrees, at.height,
                  glm::length(point - camera_.position));
    return text;
}

std::vector<std::string> ViewerSession::statusLines() const {
    std::vector<std::string> lines;
    char text[200];
    std::snprintf(
        text, sizeof text, "%s | scenario %s | %s", modeName(mode_),
        scenario_.empty() ? "(default)" : scenario_.c_str(),
        unixSeconds_
            ? ("unix time " + std::to_string(static_cast<long long>(*unixSeconds_))).c_str()
            : "render block sun");
    lines.push_back(text);
    std::snprintf(text, sizeof text, "%.6f deg %.6f deg  %.1f m above ground  speed %.1f m/s",
                  camera_.geodetic.latitude * kDegrees, camera_.geodetic.longitude * kDegrees,
                  renderer_->statistics().heightAboveTerrain, speed());
    lines.push_back(text);
    std::snprintf(
        text, sizeof text,
        "frame %.0f ms | levels %d/%d | tiles queued %zu | plants %zu | LoD %d | %.0f MiB",
        report_.milliseconds, report_.levelsDrawn, report_.levelsWanted, report_.queuedTiles,
        report_.instancesDrawn, budget_.level(), residentMegabytes());
    lines.push_back(text);
    return lines;
}

}  // namespace sylva::render
