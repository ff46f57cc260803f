// A flying camera below the ground of every resident clipmap level (issue 20, the viewer
// bench's `frames_with_holes`): an aircraft over a valley that the coarse levels, which
// average the ridges around it, fill higher than the camera, while the fine levels that
// hold the valley are still being produced. TerrainRenderer::update finds no resident
// level to stand on (standingLevel) and caps the ground near the nadir a little under the
// camera (terrain.vert's nadir ceiling); without the cap the coarse surface lies over the
// camera and rays looking down pass under it to the sky. Also: a camera just over a coarse
// level's ground whose nadir probe found a finer, much lower ground keeps a near plane
// closer than the ground drawn under it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string_view>
#include <vector>

#include "SceneRenderSupport.h"
#include "sylva/core/base/Hash.h"
#include "sylva/core/geo/Ellipsoid.h"
#include "sylva/core/scheduler/TileEvaluator.h"
#include "sylva/core/sources/raster/NormalMapSource.h"
#include "sylva/render/gl/GlContext.h"
#include "sylva/render/scene/SceneRenderer.h"

namespace sylva::render {
namespace {

constexpr double kDegree = std::numbers::pi / 180;
// Pyramid levels up to this one are ready (ring levels up to 5 have every layer, the
// height 2 and the normals 1 pyramid level coarser); finer tiles stay pending.
constexpr int kFinestReadyPyramidLevel = 4;
constexpr double kCoarseGround = 400.0;  // metres: the coarse levels' ground
constexpr double kCameraHeight = 100.0;  // metres: the camera, over true ground at 0 m

// The valley as the pyramid holds it: 400 m on the coarse levels, its true 0 m on the
// finer ones (which never arrive here).
class ValleyElevation final : public Source {
public:
    ValleyElevation() : Source("valley", "test", PortType::Elevation, 1) {
        setParameterHash(ContentHash().add(std::string_view("valley-v1")).value());
    }
    Result<TilePointer> produce(const TileKey& key, TileProvider& provider) const override {
        const TileFormat& format = provider.format();
        auto tile = std::make_shared<ImageTile>(key, format.size, format.border, 1);
        const float height = key.level <= kFinestReadyPyramidLevel ? float(kCoarseGround) : 0.0f;
        std::fill(tile->texels().begin(), tile->texels().end(), height);
        return TilePointer(tile);
    }
};

// Interactive frames ask with tryGet(): tiles finer than kFinestReadyPyramidLevel are
// "still being produced" forever (but, after holdNadir, the one under a point: the nadir
// probe finds it while its level's clipmap windows stay incomplete); the rest come from
// the synchronous evaluator.
class SlowFineTiles final : public TileProvider {
public:
    void holdNadir(double latitude, double longitude) {
        nadir_ = true;
        latitude_ = latitude;
        longitude_ = longitude;
    }
    Result<TilePointer> tile(const Source& source, const TileKey& key) override {
        return evaluator_.tile(source, key);
    }
    const TileFormat& format() const override { return evaluator_.format(); }
    TileLookup tryGet(const Source& source, const TileKey& key, int priority) override {
        if (key.level > kFinestReadyPyramidLevel && !holdsNadir(key)) {
            return {};  // pending
        }
        return TileProvider::tryGet(source, key, priority);
    }

private:
    bool holdsNadir(const TileKey& key) const {
        const double pi = std::numbers::pi;
        return nadir_ && int(std::floor((longitude_ + pi) / (2 * pi / key.columns()))) == key.x &&
               int(std::floor((pi / 2 - latitude_) / (pi / key.rows()))) == key.y;
    }
    bool nadir_ = false;
    double latitude_ = 0, longitude_ = 0;  // radians
    TileEvaluator evaluator_{TileFormat{256, 2}};
};

class CameraUnderCoarseGround : public SceneRenderFixture {
protected:
    static Camera camera(double height, double pitchDegrees) {
        Camera c;
        // Not on a tile border at any level (the nadir tile of holdNadir is one tile).
        c.geodetic = {44.3 * kDegree, 7.3 * kDegree, height};
        c.position = Ellipsoid::toEcef(c.geodetic);
        c.axes = Camera::axesFromAngles(c.geodetic, 20.0 * kDegree, pitchDegrees * kDegree, 0.0);
        c.verticalFov = 60 * kDegree;
        return c;
    }

    // Interactive frames (nothing waited for but the resident root level).
    void render(const Camera& c) {
        RenderSettings settings;
        settings.width = kWidth;
        settings.height = kHeight;
        settings.sunDirection = glm::normalize(c.position + c.axes[0] * 3.0e6 + c.axes[1] * 6.0e6);
        settings.atmosphere = false;
        settings.ocean = false;
        settings.waitForTiles = false;
        const TerrainLayers layers{&elevation_, nullptr, &normals_, {}, {}};
        for (int frame = 0; frame < 2; ++frame) {
            Result<Image> image = renderer_->render(layers, tiles_, c, settings);
            ASSERT_TRUE(image) << image.error().message;
        }
    }

    // The true ground is the ellipsoid here, so every ray the count calls deep is below the
    // horizon.
    FrameHoles countHoles(const Camera& c) const {
        return FrameHoles::count(c, renderer_->depth(), kWidth, kHeight);
    }

    static constexpr int kWidth = 320, kHeight = 180;
    ValleyElevation elevation_;
    NormalMapSource normals_{"valley.normals", &elevation_, 1.0};
    SlowFineTiles tiles_;
};

// Looking down and ahead from 300 m under the coarse ground: every ray below the horizon
// meets terrain (without the nadir ceiling 43,860, 57,600 and 57,600 of them showed sky).
TEST_F(CameraUnderCoarseGround, RaysBelowTheHorizonMeetTheGround) {
    for (const double pitch : {-20.0, -60.0, -89.0}) {
        const Camera c = camera(kCameraHeight, pitch);
        render(c);
        const TerrainFrameStatistics& terrain = renderer_->statistics().terrain;
        ASSERT_TRUE(terrain.nadirCeiling.has_value()) << "pitch " << pitch;
        EXPECT_LT(*terrain.nadirCeiling, kCameraHeight);
        EXPECT_GT(*terrain.nadirCeiling, kCameraHeight - 10.0);
        const FrameHoles count = countHoles(c);
        std::printf("pitch %5.1f: %d of %d rays under the surface show sky, ceiling %.2f m\n",
                    pitch, count.holes, count.deepRays, *terrain.nadirCeiling);
        EXPECT_GT(count.deepRays, kWidth * kHeight / 4) << "pitch " << pitch;
        EXPECT_EQ(count.holes, 0) << "pitch " << pitch << ": " << count.holes << " of "
                                  << count.deepRays << " rays under the surface show sky";
    }
}

// Above the coarse ground the resident level is stood on and nothing is capped.
TEST_F(CameraUnderCoarseGround, NoCeilingAboveTheCoarseGround) {
    const Camera c = camera(kCoarseGround + 100.0, -20.0);
    render(c);
    EXPECT_FALSE(renderer_->statistics().terrain.nadirCeiling.has_value());
    EXPECT_EQ(countHoles(c).holes, 0);
}

// A camera 1.7 m over the coarse ground (stood on: no ceiling) whose clearance the nadir
// probe takes from a finer level's tile, 401.7 m: the near plane (0.3 of the clearance)
// stays closer than the ground drawn under the camera (TerrainFrameStatistics::nadirGround).
// With 120 m it clipped that ground away and the sky showed below the horizon (the viewer
// bench's descent frames over a valley: a 6.9 m near plane, ground drawn 1.7 m below).
TEST_F(CameraUnderCoarseGround, TheNearPlaneKeepsTheGroundDrawnUnderTheCamera) {
    const Camera c = camera(kCoarseGround + 1.7, -60.0);
    tiles_.holdNadir(c.geodetic.latitude, c.geodetic.longitude);
    render(c);
    const RenderStatistics& statistics = renderer_->statistics();
    EXPECT_NEAR(statistics.groundHeight, 0.0, 1e-3);  // the probe found the fine tile
    EXPECT_FALSE(statistics.terrain.nadirCeiling.has_value());
    ASSERT_TRUE(statistics.terrain.nadirGround.has_value());
    EXPECT_NEAR(*statistics.terrain.nadirGround, kCoarseGround, 1e-3);
    EXPECT_LE(renderer_->near(), 0.3 * 1.7 + 1e-6);
    const FrameHoles count = countHoles(c);
    EXPECT_GT(count.deepRays, kWidth * kHeight / 4);
    EXPECT_EQ(count.holes, 0) << count.holes << " of " << count.deepRays
                              << " rays under the surface show sky";
}

}  // namespace
}  // namespace sylva::render
