// Where the renderer draws a surveyed point, per projection (issue 18): markers on flat
// ground at surveyed points (bench/MarkerFixture) are rendered planar (with lens shift),
// cylindrical (360°, across the strips' seams) and equirectangular (near a pole and
// across the antimeridian); each marker's detected centroid must lie within 0.5 px of
// the pixel the CPU model (ImageProjection) predicts for its ground point. Then camera
// matching on a Sylva-rendered "photograph": the detected centroids plus ±1 px noise
// recover the camera within 0.05°.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <numbers>
#include <random>

#include "sylva/bench/MarkerFixture.h"
#include "sylva/core/image/ImageWriter.h"
#include "sylva/core/scene/CameraMatcher.h"
#include "sylva/core/scene/ImageProjection.h"
#include "sylva/core/scene/PanoramaFaces.h"
#include "sylva/core/scheduler/TileEvaluator.h"
#include "sylva/render/gl/GlContext.h"
#include "sylva/render/scene/PanoramaRenderer.h"

namespace sylva::render {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDegree = kPi / 180;

class ViewProjection : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        Result<std::unique_ptr<GlContext>> created = GlContext::create({});
        ASSERT_TRUE(created) << created.error().message;
        context_ = std::move(created.value()).release();
        evaluator_ = new TileEvaluator(TileFormat{256, 2});
        Result<std::unique_ptr<SceneRenderer>> renderer =
            SceneRenderer::create(ShaderLibrary(), TerrainSettings{});
        ASSERT_TRUE(renderer) << renderer.error().message;
        renderer_ = renderer.value().release();
    }
    static void TearDownTestSuite() {
        delete renderer_;
        delete evaluator_;
        delete context_;
    }

    static Camera camera(double latitude, double longitude, double above, double heading,
                         double pitch, CameraProjection projection, double horizontalFov) {
        Camera c;
        c.geodetic = {latitude * kDegree, longitude * kDegree,
                      bench::MarkerFixture::kGroundHeight + above};
        c.position = Ellipsoid::toEcef(c.geodetic);
        c.axes = Camera::axesFromAngles(c.geodetic, heading * kDegree, pitch * kDegree, 0.0);
        c.projection = projection;
        c.horizontalFov = horizontalFov * kDegree;
        return c;
    }

    static RgbaImage render(const bench::MarkerFixture& fixture, const Camera& c, int width,
                            int height, const char* name) {
        RenderSettings settings;
        settings.width = width;
        settings.height = height;
        settings.sunDirection = glm::normalize(c.position);  // sun overhead: even light
        settings.atmosphere = false;
        settings.ocean = false;
        Result<Image> image =
            PanoramaRenderer::render(*renderer_, fixture.layers(), *evaluator_, c, settings);
        EXPECT_TRUE(image) << image.error().message;
        RgbaImage out;
        if (image) {
            out.width = image.value().width;
            out.height = image.value().height;
            out.pixels = std::move(image.value().pixels);
            const std::filesystem::path folder =
                std::filesystem::path(SYLVA_TEST_OUTPUT_DIR) / "views";
            std::filesystem::create_directories(folder);
            (void)ImageWriter::writeRgba8(folder / (std::string(name) + ".png"), out.width,
                                          out.height, out.pixels);
        }
        return out;
    }

    // Renders markers at `pixels` and returns the worst distance between a marker's
    // detected centroid and its predicted pixel.
    static double worstOffset(const Camera& c, int width, int height,
                              const std::vector<glm::dvec2>& pixels, const char* name) {
        // Search 3.5 marker radii round the prediction.
        const double window = 3.5 * bench::MarkerFixture::kAngularRadius *
                              ImageProjection(c, width, height).focalPixels();
        bench::MarkerFixture fixture;
        for (const glm::dvec2& pixel : pixels) {
            EXPECT_TRUE(fixture.addAt(c, width, height, pixel)) << name;
        }
        const RgbaImage image = render(fixture, c, width, height, name);
        const ImageProjection projection(c, width, height);
        double worst = 0.0;
        for (const bench::Marker& marker : fixture.markers()) {
            const std::optional<glm::dvec2> predicted = projection.pixelOfPoint(marker.ecef);
            EXPECT_TRUE(predicted) << name;
            if (!predicted) {
                continue;
            }
            const std::optional<glm::dvec2> found =
                bench::MarkerFixture::centroid(image, *predicted, window);
            EXPECT_TRUE(found) << name << " marker at " << predicted->x << ", " << predicted->y;
            if (found) {
                const double offset = glm::distance(*found, *predicted);
                std::printf("%-16s predicted (%8.2f, %7.2f) found (%8.2f, %7.2f) %.3f px\n", name,
                            predicted->x, predicted->y, found->x, found->y, offset);
                worst = std::max(worst, offset);
            }
        }
        return worst;
    }

    static GlContext* context_;
    static TileEvaluator* evaluator_;
    static SceneRenderer* renderer_;
};

GlContext* ViewProjection::context_ = nullptr;
TileEvaluator* ViewProjection::evaluator_ = nullptr;
SceneRenderer* ViewProjection::renderer_ = nullptr;

TEST_F(ViewProjection, PlanarWithLensShiftDrawsSurveyedPointsWhereThePinholePredicts) {
    Camera c = camera(45.0, 7.0, 300.0, 30.0, -12.0, CameraProjection::Planar, 60.0);
    c.lensShift = glm::dvec2(0.08, -0.1);
    const double worst = worstOffset(
        c, 320, 180, {{40, 40}, {160, 80}, {280, 50}, {90, 140}, {240, 130}}, "planar_shift");
    EXPECT_LT(worst, 0.5);
}

TEST_F(ViewProjection, CylindricalColumnsDrawSurveyedPointsAtTheirBearings) {
    // 360° in strips of PanoramaFaces::kMaxStripAngle: markers at every strip's centre and
    // on every seam between two strips.
    const Camera c = camera(45.0, 7.0, 300.0, 10.0, 0.0, CameraProjection::Cylindrical, 360.0);
    constexpr int kWidth = 720;
    const int strips = int(std::ceil(2 * kPi / PanoramaFaces::kMaxStripAngle - 1e-9));
    const double stripPixels = double(kWidth) / strips;
    std::vector<glm::dvec2> pixels;
    for (int i = 0; i < strips; ++i) {
        pixels.emplace_back(stripPixels * (i + 0.5), 75.0 + 8 * (i % 3));
        if (i + 1 < strips) {
            pixels.emplace_back(stripPixels * (i + 1), 90.0 - 8 * (i % 2));
        }
    }
    EXPECT_LT(worstOffset(c, kWidth, 120, pixels, "cylindrical_360"), 0.5);
}

TEST_F(ViewProjection, EquirectangularNearAPoleAndAcrossTheAntimeridian) {
    std::vector<glm::dvec2> pixels;
    for (int i = 0; i < 8; ++i) {
        pixels.emplace_back(25.0 + 90.0 * i, 215.0 + 20.0 * (i % 4));  // 15°–60° down
    }
    const Camera pole =
        camera(89.97, 40.0, 300.0, 0.0, 0.0, CameraProjection::Equirectangular, 360.0);
    EXPECT_LT(worstOffset(pole, 720, 360, pixels, "equirect_pole"), 0.5);
    const Camera date =
        camera(-12.0, 179.999, 300.0, 90.0, 0.0, CameraProjection::Equirectangular, 360.0);
    EXPECT_LT(worstOffset(date, 720, 360, pixels, "equirect_antimeridian"), 0.5);
}

TEST_F(ViewProjection, CameraMatchingRecoversTheCameraOfASylvaRenderedPhotograph) {
    // Roll is the least constrained angle (its lever arm is the points' spread in pixels):
    // at 1280 px, ±1 px of noise moves it by a few hundredths of a degree.
    constexpr int kWidth = 1280, kHeight = 720;
    // From 1.5 km up the markers lie at similar distances, so the terrain's texels blur
    // them alike (the centroids' own error stays a small fraction of a texel).
    Camera truth = camera(56.5, -4.2, 1500.0, 123.0, -25.0, CameraProjection::Planar, 0.0);
    truth.horizontalFov = 2 * std::atan(36.0 / 100.0);  // 50 mm on full frame
    truth.axes =
        Camera::axesFromAngles(truth.geodetic, 123.0 * kDegree, -25.0 * kDegree, 1.5 * kDegree);
    bench::MarkerFixture fixture;
    const glm::dvec2 spots[] = {{120, 100},  {640, 80},  {1160, 120}, {200, 380},
                                {1060, 400}, {140, 640}, {660, 600},  {1180, 660}};
    for (const glm::dvec2& spot : spots) {
        ASSERT_TRUE(fixture.addAt(truth, kWidth, kHeight, spot));
    }
    const double window = 3.5 * bench::MarkerFixture::kAngularRadius *
                          ImageProjection(truth, kWidth, kHeight).focalPixels();
    const RgbaImage photo = render(fixture, truth, kWidth, kHeight, "match_photo");
    std::mt19937 random(11);
    std::uniform_real_distribution<double> noise(-1.0, 1.0);
    std::vector<ControlPoint> points;
    for (std::size_t i = 0; i < fixture.markers().size(); ++i) {
        const std::optional<glm::dvec2> found =
            bench::MarkerFixture::centroid(photo, spots[i], window);
        ASSERT_TRUE(found);
        std::printf("marker %zu centroid off its true pixel by %.3f px\n", i + 1,
                    glm::distance(*found, spots[i]));
        points.push_back({"marker " + std::to_string(i + 1), fixture.markers()[i].ecef,
                          *found + glm::dvec2(noise(random), noise(random))});
    }
    Camera guess = truth;  // EXPECT-style first guess: a few degrees off
    guess.axes = Camera::axesFromAngles(truth.geodetic, 126.0 * kDegree, -23.0 * kDegree, 0.0);
    Result<CameraMatch> match = CameraMatcher::match(guess, kWidth, kHeight, points);
    ASSERT_TRUE(match) << match.error().message;
    const auto degrees = [](double a, double b) {
        return std::abs(std::remainder(a - b, 2 * kPi)) / kDegree;
    };
    std::printf("match: heading %.4f° pitch %.4f° roll %.4f° off, rms %.3f px\n",
                degrees(match->camera.heading(), truth.heading()),
                degrees(match->camera.pitch(), truth.pitch()),
                degrees(CameraMatcher::roll(match->camera), CameraMatcher::roll(truth)),
                match->rms);
    EXPECT_LT(degrees(match->camera.heading(), truth.heading()), 0.05);
    EXPECT_LT(degrees(match->camera.pitch(), truth.pitch()), 0.05);
    EXPECT_LT(degrees(CameraMatcher::roll(match->camera), CameraMatcher::roll(truth)), 0.05);
    EXPECT_LE(match->rms, 1.5);
}

}  // namespace
}  // namespace sylva::render
