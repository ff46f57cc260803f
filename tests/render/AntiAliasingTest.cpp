// Anti-aliasing of batch images (issue 16, SampleAccumulator): a tilted horizon of a flat
// planet against a black sky (no atmosphere) is the known edge. Checked against
//  - a CPU oracle: for every pixel, the fraction of the 2 × 2 sample rays that hit the
//    ellipsoid (double-precision ray casts), times the ground's linear value;
//  - the box filter (in linear light) of the same view rendered twice as large with one
//    sample, which the 2 × 2 grid must reproduce;
// and the single-sample image has no intermediate values along the edge.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "FlatElevation.h"
#include "sylva/core/base/Hash.h"
#include "sylva/core/geo/Ellipsoid.h"
#include "sylva/core/scheduler/TileEvaluator.h"
#include "sylva/core/sources/raster/NormalMapSource.h"
#include "sylva/render/gl/GlContext.h"
#include "sylva/render/scene/SceneRenderer.h"

namespace sylva::render {
namespace {

constexpr double kDegree = std::numbers::pi / 180;

double srgbToLinear(std::uint8_t code) {
    const double c = code / 255.0;
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

// Luminance-free: the green channel in linear light (the ground is grey).
double linearAt(const Image& image, int x, int y) {
    return srgbToLinear(image.pixels[(std::size_t(y) * image.width + x) * 4 + 1]);
}

// Distance to the WGS84 ellipsoid along a ray, or < 0 when it misses.
bool hitsEllipsoid(const glm::dvec3& origin, const glm::dvec3& direction) {
    const double a = Ellipsoid::kSemiMajorAxis, b = Ellipsoid::kSemiMinorAxis;
    const glm::dvec3 scale(1 / a, 1 / a, 1 / b);
    const glm::dvec3 o = origin * scale, d = direction * scale;
    const double qa = glm::dot(d, d), qb = glm::dot(o, d), qc = glm::dot(o, o) - 1.0;
    const double discriminant = qb * qb - qa * qc;
    return discriminant >= 0.0 && (-qb - std::sqrt(discriminant)) > 0.0;
}

class AntiAliasing : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        Result<std::unique_ptr<GlContext>> created = GlContext::create({});
        ASSERT_TRUE(created) << created.error().message;
        context_ = std::move(created.value()).release();
        elevation_ = new FlatElevation();
        normals_ = new NormalMapSource("flat.normals", elevation_, 1.0);
        evaluator_ = new TileEvaluator(TileFormat{256, 2});
        Result<std::unique_ptr<SceneRenderer>> renderer =
            SceneRenderer::create(ShaderLibrary(), TerrainSettings{});
        ASSERT_TRUE(renderer) << renderer.error().message;
        renderer_ = renderer.value().release();
    }
    static void TearDownTestSuite() {
        delete renderer_;
        delete evaluator_;
        delete normals_;
        delete elevation_;
        delete context_;
    }

    // 2 km above the ground, looking 3° down, rolled 25°: a tilted horizon line.
    static Camera camera() {
        Camera c;
        c.geodetic = {20 * kDegree, 10 * kDegree, 2000.0};
        c.position = Ellipsoid::toEcef(c.geodetic);
        c.axes = Camera::axesFromAngles(c.geodetic, 30 * kDegree, -3 * kDegree, 25 * kDegree);
        c.verticalFov = 40 * kDegree;
        return c;
    }

    static Image render(int width, int height, int samples) {
        RenderSettings settings;
        settings.width = width;
        settings.height = height;
        settings.samples = samples;
        const Camera c = camera();
        settings.sunDirection = glm::normalize(c.position);  // sun at the zenith: even ground
        settings.atmosphere = false;
        settings.ocean = false;
        TerrainLayers layers{elevation_, nullptr, normals_, {}, {}};
        Result<Image> image = renderer_->render(layers, *evaluator_, c, settings);
        EXPECT_TRUE(image) << image.error().message;
        return image ? image.value() : Image{};
    }

    // Fraction of the given sub-pixel sample rays of pixel (x, y) (rows top to bottom)
    // that hit the ground, by a CPU ray cast.
    static double groundFraction(int x, int y, int width, int height,
                                 const std::vector<glm::dvec2>& offsets) {
        const Camera c = camera();
        const double f = 1.0 / std::tan(c.verticalFov / 2);
        const double aspect = double(width) / height;
        int hits = 0;
        for (const glm::dvec2& offset : offsets) {
            const double ndcX = (x + 0.5 + offset.x) / width * 2 - 1;
            const double ndcY = ((height - 1 - y) + 0.5 + offset.y) / height * 2 - 1;
            const glm::dvec3 view(ndcX * aspect / f, ndcY / f, -1.0);
            hits += hitsEllipsoid(c.position, glm::normalize(c.axes * view)) ? 1 : 0;
        }
        return double(hits) / offsets.size();
    }

    static GlContext* context_;
    static FlatElevation* elevation_;
    static NormalMapSource* normals_;
    static TileEvaluator* evaluator_;
    static SceneRenderer* renderer_;
};

GlContext* AntiAliasing::context_ = nullptr;
FlatElevation* AntiAliasing::elevation_ = nullptr;
NormalMapSource* AntiAliasing::normals_ = nullptr;
TileEvaluator* AntiAliasing::evaluator_ = nullptr;
SceneRenderer* AntiAliasing::renderer_ = nullptr;

TEST(SampleAccumulatorPattern, GridsAndLatticesCoverThePixelEvenly) {
    EXPECT_EQ(SampleAccumulator::pattern(1), std::vector<glm::dvec2>{glm::dvec2(0.0)});
    const std::vector<glm::dvec2> four = SampleAccumulator::pattern(4);
    ASSERT_EQ(four.size(), 4u);
    EXPECT_EQ(four[0], glm::dvec2(-0.25, -0.25));
    EXPECT_EQ(four[3], glm::dvec2(0.25, 0.25));
    for (int samples = 1; samples <= SampleAccumulator::kMaxSamples; ++samples) {
        const std::vector<glm::dvec2> offsets = SampleAccumulator::pattern(samples);
        ASSERT_EQ(int(offsets.size()), samples);
        glm::dvec2 mean(0.0);
        for (const glm::dvec2& offset : offsets) {
            EXPECT_GT(offset.x, -0.5);
            EXPECT_LT(offset.x, 0.5);
            EXPECT_GT(offset.y, -0.5);
            EXPECT_LT(offset.y, 0.5);
            mean += offset / double(samples);
        }
        // Centred, and no two samples share a position.
        EXPECT_NEAR(mean.x, 0.0, 1e-12) << samples;
        EXPECT_NEAR(mean.y, 0.0, 1e-12) << samples;
        for (int i = 0; i < samples; ++i) {
            for (int j = i + 1; j < samples; ++j) {
                EXPECT_GT(glm::length(offsets[i] - offsets[j]), 0.1) << samples;
            }
        }
    }
}

TEST_F(AntiAliasing, EdgePixelsAverageTheirSamplesAndMatchTheBoxFilteredLargerImage) {
    constexpr int kWidth = 160, kHeight = 90;
    const Image single = render(kWidth, kHeight, 1);
    const Image four = render(kWidth, kHeight, 4);
    const Image large = render(2 * kWidth, 2 * kHeight, 1);
    ASSERT_FALSE(single.pixels.empty());
    ASSERT_FALSE(four.pixels.empty());
    ASSERT_FALSE(large.pixels.empty());
    // The ground's linear value: the bottom-centre pixel, far below the horizon.
    const double ground = linearAt(four, kWidth / 2, kHeight - 3);
    ASSERT_GT(ground, 0.1);
    const std::vector<glm::dvec2> grid = SampleAccumulator::pattern(4);
    int edgePixels = 0, intermediateFour = 0, intermediateSingle = 0, offOracle = 0, offBox = 0;
    double worstOracle = 0, worstBox = 0, sumBox = 0;
    for (int y = 0; y < kHeight; ++y) {
        for (int x = 0; x < kWidth; ++x) {
            const double fraction = groundFraction(x, y, kWidth, kHeight, grid);
            const double value = linearAt(four, x, y);
            double box = 0;
            for (int dy = 0; dy < 2; ++dy) {
                for (int dx = 0; dx < 2; ++dx) {
                    box += linearAt(large, 2 * x + dx, 2 * y + dy) / 4;
                }
            }
            worstBox = std::max(worstBox, std::abs(value - box));
            offBox += std::abs(value - box) > 0.02 ? 1 : 0;
            sumBox += std::abs(value - box);
            if (fraction > 0.0 && fraction < 1.0) {
                ++edgePixels;
                worstOracle = std::max(worstOracle, std::abs(value - fraction * ground));
                offOracle += std::abs(value - fraction * ground) > 0.02 ? 1 : 0;
                intermediateFour += (value > 0.15 * ground && value < 0.85 * ground) ? 1 : 0;
                const double one = linearAt(single, x, y);
                intermediateSingle += (one > 0.15 * ground && one < 0.85 * ground) ? 1 : 0;
            }
        }
    }
    // The horizon crosses the whole image at 25°: about 160 / cos 25° ≈ 180 pixel steps,
    // ~120 of them with 1..3 of the 4 samples on the ground.
    EXPECT_GT(edgePixels, 100);
    EXPECT_GT(intermediateFour, edgePixels / 2);
    EXPECT_LT(intermediateSingle, edgePixels / 20);
    // Every pixel is its samples' average. A sample lying on the edge to within float
    // precision may fall either way (seen: 2 of ~120 pixels), so a few pixels may be one
    // sample (a quarter of the ground) off; no more.
    EXPECT_LE(offOracle, edgePixels / 25);
    EXPECT_LE(offBox, edgePixels / 25);
    EXPECT_LT(worstOracle, 0.25 * ground + 0.02);
    EXPECT_LT(worstBox, 0.25 * ground + 0.02);
    EXPECT_LT(sumBox / (kWidth * kHeight), 0.002);
}

TEST_F(AntiAliasing, RadianceIsAveragedToo) {
    RenderSettings settings;
    settings.width = 64;
    settings.height = 36;
    settings.samples = 4;
    settings.linearOutput = true;
    const Camera c = camera();
    settings.sunDirection = glm::normalize(c.position);
    settings.atmosphere = false;
    settings.ocean = false;
    TerrainLayers layers{elevation_, nullptr, normals_, {}, {}};
    Result<Image> image = renderer_->render(layers, *evaluator_, c, settings);
    ASSERT_TRUE(image) << image.error().message;
    ASSERT_EQ(image.value().radiance.size(), std::size_t(64 * 36 * 4));
    // Every pixel: the display value is the average of the tone-mapped samples, so it is at
    // most the tone map of the averaged radiance (Jensen: 1 − exp(−x) is concave), and both
    // are 0 in the sky and equal on uniform ground.
    for (int i = 0; i < 64 * 36; ++i) {
        const double radiance = image.value().radiance[std::size_t(i) * 4 + 1];
        const double display = srgbToLinear(image.value().pixels[std::size_t(i) * 4 + 1]);
        EXPECT_LE(display, 1.0 - std::exp(-radiance) + 0.01) << i;
    }
}

TEST_F(AntiAliasing, SampleCountsOutsideTheRangeAreErrors) {
    for (int samples : {0, 17, 100}) {
        RenderSettings settings;
        settings.width = 32;
        settings.height = 18;
        settings.samples = samples;
        TerrainLayers layers{elevation_, nullptr, normals_, {}, {}};
        Result<Image> image = renderer_->render(layers, *evaluator_, camera(), settings);
        ASSERT_FALSE(image);
        EXPECT_NE(image.error().message.find("samples"), std::string::npos);
    }
}

}  // namespace
}  // namespace sylva::render
