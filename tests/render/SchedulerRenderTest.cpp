// The terrain fed by the concurrent Scheduler (seed 001 Algorithm 3): batch frames
// (waitForTiles) are bit-identical to the synchronous TileEvaluator's, whatever the
// thread timing; interactive frames draw the levels that are ready, never fail while
// tiles are pending, and converge to the batch image once the workers caught up.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <thread>

#include "sylva/core/base/Hash.h"
#include "sylva/core/geo/Ellipsoid.h"
#include "sylva/core/scheduler/Scheduler.h"
#include "sylva/core/scheduler/TileEvaluator.h"
#include "sylva/core/sources/raster/NormalMapSource.h"
#include "sylva/render/gl/GlContext.h"
#include "sylva/render/scene/SceneRenderer.h"

namespace sylva::render {
namespace {

constexpr double kDegree = std::numbers::pi / 180;

double hills(double latitude, double longitude) {
    const glm::dvec3 d = Ellipsoid::surfaceNormal(latitude, longitude);
    const double k = 2 * std::numbers::pi * Ellipsoid::kMeanRadius / 20000.0;
    return 600.0 * std::sin(k * d.x) * std::sin(k * d.y) * std::sin(k * d.z) + 500.0;
}

// Analytic hills; `delay` makes each tile slow, so workers lag behind the frames.
class HillSource final : public Source {
public:
    explicit HillSource(std::chrono::milliseconds delay)
        : Source("hills", "test", PortType::Elevation, 1), delay_(delay) {
        setParameterHash(ContentHash().add(std::string_view("hills-v1")).value());
    }
    Result<TilePointer> produce(const TileKey& key, TileProvider& provider) const override {
        std::this_thread::sleep_for(delay_);
        const TileFormat& format = provider.format();
        auto tile = std::make_shared<ImageTile>(key, format.size, format.border, 1);
        for (int iy = -format.border; iy < format.size + format.border; ++iy) {
            for (int ix = -format.border; ix < format.size + format.border; ++ix) {
                tile->at(ix, iy, 0) =
                    float(hills(tile->texelLatitude(iy), tile->texelLongitude(ix)));
            }
        }
        return TilePointer(tile);
    }

private:
    std::chrono::milliseconds delay_;
};

Camera cameraAt(double latitude, double longitude, double aboveGround) {
    Camera c;
    c.geodetic = {latitude * kDegree, longitude * kDegree,
                  hills(latitude * kDegree, longitude * kDegree) + aboveGround};
    c.position = Ellipsoid::toEcef(c.geodetic);
    c.axes = Camera::axesFromAngles(c.geodetic, 30 * kDegree, -20 * kDegree, 0.0);
    c.verticalFov = 60 * kDegree;
    return c;
}

RenderSettings settingsFor(const Camera& c, bool waitForTiles) {
    RenderSettings settings;
    settings.width = 160;
    settings.height = 90;
    settings.sunDirection = glm::normalize(c.position + c.axes[0] * 3.0e6 + c.axes[1] * 6.0e6);
    settings.atmosphere = false;
    settings.ocean = false;
    settings.waitForTiles = waitForTiles;
    return settings;
}

TEST(SchedulerRender, BatchFramesEqualTheSynchronousEvaluatorAndInteractiveOnesConverge) {
    Result<std::unique_ptr<GlContext>> context = GlContext::create({});
    ASSERT_TRUE(context) << context.error().message;
    const HillSource elevation(std::chrono::milliseconds(2));
    const NormalMapSource normals("hills.normals", &elevation, 1.0);
    const TerrainLayers layers{&elevation, nullptr, &normals, {}, {}};
    Result<std::unique_ptr<SceneRenderer>> reference =
        SceneRenderer::create(ShaderLibrary(), TerrainSettings{});
    Result<std::unique_ptr<SceneRenderer>> batch =
        SceneRenderer::create(ShaderLibrary(), TerrainSettings{});
    Result<std::unique_ptr<SceneRenderer>> interactive =
        SceneRenderer::create(ShaderLibrary(), TerrainSettings{});
    ASSERT_TRUE(reference && batch && interactive);
    TileEvaluator evaluator(TileFormat{256, 2});
    SchedulerOptions options;
    options.format = TileFormat{256, 2};
    options.workers = 3;
    Scheduler batchScheduler(options);
    Scheduler interactiveScheduler(options);

    // A short walk: each frame moves the focus so levels need new tiles.
    int waitingFrames = 0;
    for (int frame = 0; frame < 4; ++frame) {
        const Camera c =
            cameraAt(-8.0 + 0.01 * frame, -34.9 + 0.013 * frame, 300.0 + 200.0 * frame);
        Result<Image> expected =
            reference.value()->render(layers, evaluator, c, settingsFor(c, true));
        Result<Image> scheduled =
            batch.value()->render(layers, batchScheduler, c, settingsFor(c, true));
        ASSERT_TRUE(expected && scheduled);
        EXPECT_EQ(expected->pixels, scheduled->pixels) << "frame " << frame;
        EXPECT_EQ(batch.value()->statistics().terrain.waitingLevel, -1);

        Result<Image> quick =
            interactive.value()->render(layers, interactiveScheduler, c, settingsFor(c, false));
        ASSERT_TRUE(quick) << quick.error().message;
        const TerrainFrameStatistics& statistics = interactive.value()->statistics().terrain;
        EXPECT_TRUE(statistics.degraded.empty()) << statistics.degraded;
        EXPECT_GE(statistics.levels.finest, statistics.wanted.coarsest);
        if (statistics.waitingLevel >= 0) {
            ++waitingFrames;
            // Interactive frames draw every wanted ring; rings finer than the resident
            // level sample it, so a level still being produced is never sampled.
            EXPECT_EQ(statistics.levels.finest, statistics.wanted.finest);
            if (statistics.waitingLevel >= std::max(0, statistics.wanted.coarsest - 1)) {
                EXPECT_LT(statistics.textureLevel, statistics.waitingLevel);
            }
        }
    }
    // 2 ms per tile and dozens of tiles per focus: the first interactive frames cannot
    // have had every level ready.
    EXPECT_GT(waitingFrames, 0);
    // Once the workers caught up, the interactive frame is the batch frame.
    const Camera last = cameraAt(-8.0 + 0.03, -34.9 + 0.039, 900.0);
    for (int attempt = 0; attempt < 50; ++attempt) {
        interactiveScheduler.waitIdle();
        Result<Image> quick = interactive.value()->render(layers, interactiveScheduler, last,
                                                          settingsFor(last, false));
        ASSERT_TRUE(quick);
        if (interactive.value()->statistics().terrain.waitingLevel < 0) {
            Result<Image> expected =
                reference.value()->render(layers, evaluator, last, settingsFor(last, true));
            ASSERT_TRUE(expected);
            EXPECT_EQ(expected->pixels, quick->pixels);
            return;
        }
    }
    FAIL() << "the interactive frame never got all its levels";
}

}  // namespace
}  // namespace sylva::render
