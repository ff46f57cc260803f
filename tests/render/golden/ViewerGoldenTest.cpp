// The viewer (render::Viewer) driven by scripts, headless on llvmpipe (EGL; the window
// path is exercised under Xvfb by tests/app/viewer_cli_test.sh), on
// tests/render/viewer/viewer.sylva at 320x180:
// - a project camera shown by the viewer equals the batch image of that camera (RMSE
//   <= 1) and its golden `viewer_aircraft`; a flight with a scenario switch and a time change gives
//   the `viewer_flown` golden; the camera saved into the project (through the
//   formatter: the file's comments are kept) renders in batch (`sylva render`'s
//   BatchRenderer) to the viewer's screenshot within RMSE 1.5;
// - hot reload: an edit of the project shows in the next frames (`frames 2`) and
//   equals a batch render of the edited project; a broken edit keeps the last good
//   image;
// - a swipe between the two scenarios with the atmosphere layer off (`viewer_swipe`).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>

#include "GoldenImage.h"
#include "sylva/core/geo/Ellipsoid.h"
#include "sylva/core/image/ImageWriter.h"
#include "sylva/core/scene/ViewerScript.h"
#include "sylva/core/scheduler/Scheduler.h"
#include "sylva/core/sources/objects/MeshSource.h"
#include "sylva/core/terrain/ElevationQuery.h"
#include "sylva/dsl/CameraBlockEditor.h"
#include "sylva/dsl/ProjectLoader.h"
#include "sylva/render/batch/BatchRenderer.h"
#include "sylva/render/viewer/Viewer.h"

namespace sylva::render {
namespace {

constexpr int kWidth = 320;
constexpr int kHeight = 180;
constexpr double kDegree = std::numbers::pi / 180.0;

class TestHost final : public ViewerHost {
public:
    explicit TestHost(std::filesystem::path project) : project_(std::move(project)) {}
    Result<std::vector<ProjectModel>> loadProject() override {
        dsl::LoadResult loaded = dsl::loadProject(project_);
        files_ = loaded.files;
        if (loaded.hasErrors() || !loaded.model) {
            return Error{loaded.render()};
        }
        return loaded.scenarios;
    }
    std::vector<std::filesystem::path> projectFiles() const override { return files_; }
    Status saveCamera(const std::string& name, const Camera& camera,
                      const std::string& views) override {
        return dsl::CameraBlockEditor::save(project_, name, camera, views);
    }

private:
    std::filesystem::path project_;
    std::vector<std::filesystem::path> files_;
};

class SilentListener final : public BatchListener {
public:
    void jobDone(const JobReport&) override {}
    void error(const std::string& message) override { ADD_FAILURE() << message; }
};

std::string readText(const std::filesystem::path& file) {
    std::ifstream in(file);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

// A scratch folder holding a copy of the viewer test project and `script`.
std::filesystem::path prepare(const std::string& name, const std::string& script) {
    const std::filesystem::path folder =
        std::filesystem::path(SYLVA_TEST_OUTPUT_DIR) / "viewer" / name;
    std::filesystem::remove_all(folder);
    std::filesystem::create_directories(folder);
    std::filesystem::copy_file(
        std::filesystem::path(SYLVA_TEST_DATA_DIR) / "render" / "viewer" / "viewer.sylva",
        folder / "viewer.sylva");
    std::ofstream(folder / "run.script") << script;
    return folder;
}

// Runs the script of `folder` in a headless viewer (`onFrame` sees every interactive
// frame); returns the viewer's status.
Status runViewer(const std::filesystem::path& folder,
                 std::function<void(const ViewerFrame&)> onFrame = {}) {
    TestHost host(folder / "viewer.sylva");
    Result<std::vector<ProjectModel>> models = host.loadProject();
    if (!models) {
        return models.error();
    }
    BatchOptions options;
    options.width = kWidth;
    options.height = kHeight;
    BatchRenderer batch(options);
    if (Status set = batch.setProject(std::move(models.value())); !set) {
        return set;
    }
    Result<std::vector<ScriptCommand>> script = ViewerScript::load(folder / "run.script");
    if (!script) {
        return script.error();
    }
    ViewerOptions viewerOptions;
    viewerOptions.script = std::move(script.value());
    viewerOptions.closeAfterScript = true;
    viewerOptions.onFrame = std::move(onFrame);
    Viewer viewer(batch, host, viewerOptions);
    return viewer.run();
}

// The batch image of camera `camera` in views block `views` of the project in `folder`.
std::vector<std::uint8_t> renderBatch(const std::filesystem::path& folder, const std::string& views,
                                      const std::string& camera) {
    dsl::LoadResult loaded = dsl::loadProject(folder / "viewer.sylva");
    EXPECT_FALSE(loaded.hasErrors()) << loaded.render();
    BatchRenderer batch;
    EXPECT_TRUE(batch.setProject(loaded.scenarios));
    BatchSelection selection;
    selection.outputFolder = folder / "batch";
    selection.views = views;
    selection.viewpoint = camera;
    selection.manifest = false;
    selection.comparisons = false;
    Result<BatchPlan> plan = batch.plan(selection);
    EXPECT_TRUE(plan) << (plan ? "" : plan.error().message);
    if (!plan) {
        return {};
    }
    EXPECT_EQ(plan->jobs().size(), 1u);
    SilentListener listener;
    Result<BatchSummary> summary = batch.run(plan.value(), listener);
    EXPECT_TRUE(summary && summary->failed == 0);
    int width = 0, height = 0;
    Result<std::vector<std::uint8_t>> pixels =
        ImageWriter::readRgba8(plan->jobs().front().output, width, height);
    EXPECT_TRUE(pixels) << (pixels ? "" : pixels.error().message);
    return pixels ? pixels.value() : std::vector<std::uint8_t>{};
}

std::vector<std::uint8_t> readImage(const std::filesystem::path& file) {
    int width = 0, height = 0;
    Result<std::vector<std::uint8_t>> pixels = ImageWriter::readRgba8(file, width, height);
    EXPECT_TRUE(pixels) << (pixels ? "" : pixels.error().message);
    EXPECT_EQ(width, kWidth);
    EXPECT_EQ(height, kHeight);
    return pixels ? pixels.value() : std::vector<std::uint8_t>(kWidth * kHeight * 4, 0);
}

// The project of `folder` loaded as `sylva render` does, and the walker tests' ground oracle:
// an ElevationQuery on its own Scheduler over the "natural" terrain (query destroyed first).
struct ProjectGround {
    dsl::LoadResult loaded;
    BatchRenderer batch;
    Scheduler tiles;
    std::optional<ElevationQuery> query;
};

// Fills `ground`; fatal failures when the project does not load or has no "natural"
// terrain (call under ASSERT_NO_FATAL_FAILURE).
void loadGround(const std::filesystem::path& folder, ProjectGround& ground) {
    ground.loaded = dsl::loadProject(folder / "viewer.sylva");
    ASSERT_FALSE(ground.loaded.hasErrors()) << ground.loaded.render();
    ASSERT_TRUE(ground.batch.setProject(ground.loaded.scenarios));
    Result<TerrainLayers> layers = ground.batch.project().terrainLayers("natural");
    ASSERT_TRUE(layers) << layers.error().message;
    ground.query.emplace(*layers->elevation, ground.tiles);
}

double meanLevel(const std::vector<std::uint8_t>& pixels) {
    double sum = 0;
    for (std::size_t i = 0; i < pixels.size(); i += 4) {
        sum += pixels[i] + pixels[i + 1] + pixels[i + 2];
    }
    return sum / (pixels.size() / 4 * 3);
}

TEST(ViewerGolden, ScriptedFlightSavesACameraThatRendersTheSameInBatch) {
    const std::filesystem::path folder =
        prepare("flight", readText(std::filesystem::path(SYLVA_TEST_DATA_DIR) / "render" /
                                   "viewer" / "flight.script"));
    const Status ran = runViewer(folder);
    ASSERT_TRUE(ran) << ran.error().message;

    const std::vector<std::uint8_t> aircraft = readImage(folder / "aircraft.png");
    golden::checkGolden("viewer_aircraft", kWidth, kHeight, aircraft);
    // The viewer shows a project camera exactly as the batch renders it.
    const golden::Comparison sameCamera =
        golden::compareImages(aircraft, renderBatch(folder, "overview", "aircraft"), nullptr);
    EXPECT_LE(sameCamera.rmse, 1.0);

    const std::vector<std::uint8_t> flown = readImage(folder / "flown.png");
    golden::checkGolden("viewer_flown", kWidth, kHeight, flown);
    const golden::Comparison differs = golden::compareImages(aircraft, flown, nullptr);
    EXPECT_GT(differs.rmse, 10.0) << "the flight, scenario and time changed nothing";

    // The saved camera: a formatted block in the file (comments kept), listed in `check`.
    const std::string text = readText(folder / "viewer.sylva");
    EXPECT_NE(text.find("camera flown {"), std::string::npos) << text;
    EXPECT_NE(text.find("cameras = [@aircraft, @flown]"), std::string::npos) << text;
    EXPECT_NE(text.find("# The hot-reload test edits this brightness"), std::string::npos);
    const golden::Comparison batch =
        golden::compareImages(flown, renderBatch(folder, "check", "flown"), nullptr);
    EXPECT_LE(batch.rmse, 1.5) << "max error " << batch.maxError;
}

TEST(ViewerGolden, AnEditShowsWithinTwoFramesAndABrokenEditKeepsTheLastGoodState) {
    const std::filesystem::path folder =
        prepare("reload",
                "camera aircraft\n"
                "wait-tiles\n"
                "screenshot before.png\n"
                "edit viewer.sylva \"brightness = 0\" \"brightness = 0.25\"\n"
                "frames 2\n"
                "screenshot after.png\n"
                "edit viewer.sylva \"brightness = 0.25\" \"brightness = @nowhere\"\n"
                "frames 2\n"
                "screenshot kept.png\n");
    const Status ran = runViewer(folder);
    ASSERT_TRUE(ran) << ran.error().message;
    const std::vector<std::uint8_t> before = readImage(folder / "before.png");
    const std::vector<std::uint8_t> after = readImage(folder / "after.png");
    EXPECT_GT(meanLevel(after), meanLevel(before) + 5.0) << "the brightness edit did not show";
    // The reloaded view equals a batch render of the edited project.
    std::string edited = readText(folder / "viewer.sylva");
    const std::size_t broken = edited.find("brightness = @nowhere");
    ASSERT_NE(broken, std::string::npos);
    edited.replace(broken, 21, "brightness = 0.25");
    std::ofstream(folder / "viewer.sylva") << edited;
    const golden::Comparison reloaded =
        golden::compareImages(after, renderBatch(folder, "overview", "aircraft"), nullptr);
    EXPECT_LE(reloaded.rmse, 1.0);
    // The broken edit kept the last good state.
    const golden::Comparison kept =
        golden::compareImages(after, readImage(folder / "kept.png"), nullptr);
    EXPECT_LE(kept.rmse, 0.5);
}

// The comparison modes live: the two scenarios swiped at the middle (natural colour left,
// the desaturated `dry` right, a light divider), atmosphere switched off (black sky).
TEST(ViewerGolden, SwipeBetweenScenariosWithALayerOff) {
    const std::filesystem::path folder = prepare("swipe",
                                                 "camera aircraft\n"
                                                 "compare swipe dry 0.5\n"
                                                 "layer atmosphere off\n"
                                                 "screenshot swipe.png\n");
    const Status ran = runViewer(folder);
    ASSERT_TRUE(ran) << ran.error().message;
    const std::vector<std::uint8_t> swipe = readImage(folder / "swipe.png");
    golden::checkGolden("viewer_swipe", kWidth, kHeight, swipe);
    // Top-left is sky: black without the atmosphere.
    EXPECT_LT(swipe[0] + swipe[1] + swipe[2], 30);
}

// Issue 20: a walker standing still reaches full detail. The viewer once placed the walker
// on the level it last drew from, and the renderer drew from the finest level whose ground
// was below the walker: on a hill every finer level's ground was above it, so the drawn
// level stayed coarse forever (the bench: level 8 of 24 for minutes), and once the nadir
// tile of the finest level arrived the frame failed ("camera below the terrain"). Now
// `wait-tiles` must end (nothing pending) with the finest wanted level drawn and the eye
// 1.7 m over that level's ground (ElevationQuery on its own Scheduler: the oracle).
TEST(ViewerGolden, AStillWalkerReachesTheFinestLevelOnItsGround) {
    const std::filesystem::path folder =
        prepare("walker", "camera aircraft\nmode walk\nwait-tiles\n");
    std::vector<ViewerFrame> frames;
    Camera last;
    const Status ran = runViewer(folder, [&](const ViewerFrame& frame) {
        frames.push_back(frame);
        last = *frame.camera;
    });
    ASSERT_TRUE(ran) << ran.error().message;
    ASSERT_FALSE(frames.empty());
    const ViewerFrame& final = frames.back();
    EXPECT_FALSE(final.pending);
    EXPECT_EQ(final.levelsWanted, 24);
    EXPECT_EQ(final.levelsDrawn, final.levelsWanted)
        << "after " << frames.size() << " frames the terrain is drawn from level "
        << final.levelsDrawn;
    // The drawn level rose monotonically once the walker stood still (no re-ordering).
    for (std::size_t i = 2; i < frames.size(); ++i) {
        EXPECT_GE(frames[i].levelsDrawn, frames[i - 1].levelsDrawn) << "frame " << i;
    }

    ProjectGround project;
    ASSERT_NO_FATAL_FAILURE(loadGround(folder, project));
    const ElevationQuery& query = *project.query;
    Result<double> ground =
        query.groundHeight(last.geodetic.latitude, last.geodetic.longitude, final.levelsWanted);
    ASSERT_TRUE(ground) << ground.error().message;
    // The spot is one where the old placement stalled: some coarse level's ground lies
    // more than the eye height under every finer level's (a hill seen coarsely).
    bool stalls = false;
    std::string grounds;
    for (int level = 4; level < final.levelsWanted && !stalls; ++level) {
        const double coarse =
            query.groundHeight(last.geodetic.latitude, last.geodetic.longitude, level).value();
        double finer = 1e30;
        for (int other = level + 1; other <= final.levelsWanted; ++other) {
            finer = std::min(
                finer,
                query.groundHeight(last.geodetic.latitude, last.geodetic.longitude, other).value());
        }
        // Appended piecewise: GCC 12's -Wrestrict misfires on chains of `+`.
        grounds.append(" ")
            .append(std::to_string(level))
            .append(":")
            .append(std::to_string(coarse));
        stalls = std::max(coarse, 0.0) + 1.7 < std::max(finer, 0.0);
    }
    EXPECT_TRUE(stalls) << "grounds by level:" << grounds;
    // The project has an ocean: the walker stands on the sea surface there.
    EXPECT_NEAR(last.geodetic.height, std::max(ground.value(), 0.0) + 1.7, 1e-3);
}

// A walker saved one frame after arriving, before the fine tiles came, is written on the
// finest level's ground (as the screenshot stands it), so the batch renders it.
TEST(ViewerGolden, AWalkerSavedBeforeItsTilesArriveIsSavedOnTheFinestGround) {
    const std::filesystem::path folder = prepare(
        "walker_saved", "camera aircraft\nmode walk\nframes 1\nsave-camera walker check\nquit\n");
    const Status ran = runViewer(folder);
    ASSERT_TRUE(ran) << ran.error().message;

    ProjectGround project;
    ASSERT_NO_FATAL_FAILURE(loadGround(folder, project));
    const ElevationQuery& query = *project.query;
    const Block* block = project.loaded.scenarios.front().findCamera("walker");
    ASSERT_NE(block, nullptr);
    const Camera::TerrainHeight noTerrain = [](double, double) -> Result<double> { return 0.0; };
    Result<Camera> saved = Camera::fromBlock(*block, noTerrain);
    ASSERT_TRUE(saved) << saved.error().message;
    // The finest level a walker's view wants (AStillWalkerReachesTheFinestLevelOnItsGround).
    constexpr int kFinestLevel = 24;
    Result<double> ground =
        query.groundHeight(saved->geodetic.latitude, saved->geodetic.longitude, kFinestLevel);
    ASSERT_TRUE(ground) << ground.error().message;
    EXPECT_NEAR(saved->geodetic.height, std::max(ground.value(), 0.0) + 1.7, 1e-3);
    EXPECT_FALSE(renderBatch(folder, "check", "walker").empty());
}

// The village fixture's copy (absolute data paths) with a camera 400 m above the ellipsoid,
// over the flat roof of house 4, looking west toward house 2.
std::filesystem::path prepareVillage(const std::string& name, const std::string& script) {
    const std::filesystem::path folder = prepare(name, script);
    const std::filesystem::path golden =
        std::filesystem::path(SYLVA_TEST_DATA_DIR) / "render" / "golden";
    std::string text = readText(golden / "village.sylva");
    for (const std::string key : {"file = \"", "model = \""}) {
        for (std::size_t at = text.find(key); at != std::string::npos;
             at = text.find(key, at + key.size())) {
            text.insert(at + key.size(), golden.string() + "/");
        }
    }
    text +=
        "camera roof {\n    position = geo(10.0001266deg, 20.0deg, 400m)\n"
        "    heading = 270deg\n    pitch = -5deg\n    fov = 60deg\n}\n";
    std::ofstream(folder / "viewer.sylva") << text;
    return folder;
}

// Walk mode among the proposal's buildings (issue 20: "eye height kept above terrain and
// objects"): a walker dropped from a flight over house 4 stands on its flat roof (the
// roof's height from the buildings source's own triangles), walks west off it onto the
// terrain and is stopped 0.3 m short of house 2's east wall (the footprint's longitude in
// village_buildings.geojson), which then fills the view uncut by the near plane.
TEST(ViewerGolden, AWalkerStandsOnARoofAndIsStoppedByAWall) {
    const std::filesystem::path folder =
        prepareVillage("walker_village",
                       "camera roof\nwait-tiles\nmode walk\nwait-tiles\nsave-camera on_roof\n"
                       "fly 40 0 0\nwait-tiles\nsave-camera at_wall\nquit\n");
    int levelsWanted = 0;
    double centreDistance = 0;  // along the view axis, of the last frame's centre pixel
    const Status ran = runViewer(folder, [&](const ViewerFrame& frame) {
        levelsWanted = frame.levelsWanted;
        const float depth =
            (*frame.depth)[std::size_t(frame.height / 2) * frame.width + frame.width / 2];
        centreDistance = depth > 0.0f ? frame.near / depth : 1e30;
    });
    ASSERT_TRUE(ran) << ran.error().message;

    dsl::LoadResult loaded = dsl::loadProject(folder / "viewer.sylva");
    ASSERT_FALSE(loaded.hasErrors()) << loaded.render();
    const Camera::TerrainHeight noTerrain = [](double, double) -> Result<double> { return 0.0; };
    const Block* onRoofBlock = loaded.scenarios.front().findCamera("on_roof");
    const Block* atWallBlock = loaded.scenarios.front().findCamera("at_wall");
    ASSERT_TRUE(onRoofBlock && atWallBlock);
    const Camera onRoof = Camera::fromBlock(*onRoofBlock, noTerrain).value();
    const Camera atWall = Camera::fromBlock(*atWallBlock, noTerrain).value();

    // The roof: the highest vertex of the village tile inside house 4's footprint.
    BatchRenderer batch;
    ASSERT_TRUE(batch.setProject(loaded.scenarios));
    Result<TerrainLayers> layers = batch.project().terrainLayers("village");
    ASSERT_TRUE(layers) << layers.error().message;
    Scheduler tiles;
    const MeshSource* houses = MeshSource::from(layers->meshes.front());
    ASSERT_NE(houses, nullptr);
    const glm::dvec2 roofCentre(20.0 * kDegree, 10.0001266 * kDegree);
    Result<std::shared_ptr<const MeshTile>> tile =
        houses->tile(MeshSource::keyOf(roofCentre), tiles);
    ASSERT_TRUE(tile) << tile.error().message;
    double roof = -1e30;
    for (const MeshVertex& vertex : tile.value()->geometry.vertices) {
        const Geodetic at =
            Ellipsoid::toGeodetic(tile.value()->origin + glm::dvec3(vertex.position));
        if (at.longitude > 19.999926 * kDegree && at.longitude < 20.000074 * kDegree &&
            at.latitude > 10.0000813 * kDegree && at.latitude < 10.0001719 * kDegree) {
            roof = std::max(roof, at.height);
        }
    }
    EXPECT_NEAR(onRoof.geodetic.height, roof + 1.7, 0.01);

    // Stopped 0.3 m east of house 2's east wall, 40 m asked, on the terrain there.
    const double metresPerDegree = Ellipsoid::primeVerticalRadius(atWall.geodetic.latitude) *
                                   std::cos(atWall.geodetic.latitude) * kDegree;
    EXPECT_NEAR((atWall.geodetic.longitude / kDegree - 19.999772) * metresPerDegree, 0.3, 0.01);
    EXPECT_NEAR(atWall.geodetic.latitude, onRoof.geodetic.latitude, 1e-9);
    // The wall fills the view at 0.3 m (pitch -5°): the near plane does not cut it open
    // (at 0.3 x the eye height, 0.51 m, the centre showed the house's far wall inside).
    EXPECT_NEAR(centreDistance, 0.3 / std::cos(5.0 * kDegree), 0.02);
    const ElevationQuery query(*layers->elevation, tiles);
    Result<double> ground =
        query.groundHeight(atWall.geodetic.latitude, atWall.geodetic.longitude, levelsWanted);
    ASSERT_TRUE(ground) << ground.error().message;
    EXPECT_NEAR(atWall.geodetic.height, ground.value() + 1.7, 1e-3);
}

}  // namespace
}  // namespace sylva::render
