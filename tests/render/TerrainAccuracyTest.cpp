// The spherical clipmap terrain against a CPU reference (issue: terrain accuracy).
// An analytic elevation h(lat, lon) is rendered; for every pixel the distance
// reconstructed from the reversed-Z depth buffer is compared with a CPU ray cast of
// the true surface in double precision. Also: moving the camera by 1 cm changes the
// image only slightly (no jitter), at mid-latitudes, the poles and the antimeridian.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "FlatElevation.h"
#include "SceneRenderSupport.h"
#include "sylva/core/base/Hash.h"
#include "sylva/core/geo/Ellipsoid.h"
#include "sylva/core/scheduler/TileEvaluator.h"
#include "sylva/core/sources/raster/NormalMapSource.h"
#include "sylva/core/terrain/ElevationQuery.h"
#include "sylva/render/gl/GlContext.h"
#include "sylva/render/scene/SceneRenderer.h"

namespace sylva::render {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDegree = kPi / 180;

// Hills of ~15 km wavelength defined on the unit sphere (so also at the poles):
// h = 700 m * sin(k x) sin(k y) sin(k z) + 400 m for the unit direction (x, y, z).
double analyticHeight(double latitude, double longitude) {
    const glm::dvec3 d = Ellipsoid::surfaceNormal(latitude, longitude);
    const double k = 2 * kPi * Ellipsoid::kMeanRadius / 15000.0;
    return 700.0 * std::sin(k * d.x) * std::sin(k * d.y) * std::sin(k * d.z) + 400.0;
}

class AnalyticElevation final : public Source {
public:
    explicit AnalyticElevation(double offset = 0.0)
        : Source("analytic", "test", PortType::Elevation, 1), offset_(offset) {
        setParameterHash(ContentHash().add(std::string_view("analytic-v1")).add(offset).value());
    }
    Result<TilePointer> produce(const TileKey& key, TileProvider& provider) const override {
        const TileFormat& format = provider.format();
        auto tile = std::make_shared<ImageTile>(key, format.size, format.border, 1);
        for (int iy = -format.border; iy < format.size + format.border; ++iy) {
            for (int ix = -format.border; ix < format.size + format.border; ++ix) {
                tile->at(ix, iy, 0) = float(
                    analyticHeight(tile->texelLatitude(iy), tile->texelLongitude(ix)) + offset_);
            }
        }
        return TilePointer(tile);
    }

private:
    double offset_;
};

// Distance along `direction` (unit, ECEF) from `origin` to the analytic surface, or
// a negative value when the ray does not hit it within `maxDistance`.
double rayCast(const glm::dvec3& origin, const glm::dvec3& direction, double maxDistance) {
    const auto above = [&](double t) {
        const Geodetic g = Ellipsoid::toGeodetic(origin + direction * t);
        return g.height - analyticHeight(g.latitude, g.longitude);
    };
    double t = 0.0;
    double previous = above(0.0);
    if (previous <= 0.0) {
        return 0.0;
    }
    while (t < maxDistance) {
        const double step = std::max(0.5, std::min(previous * 0.5 + t * 0.002, 2000.0));
        const double next = t + step;
        const double value = above(next);
        if (value <= 0.0) {
            double low = t, high = next;
            for (int i = 0; i < 60 && high - low > 1e-4 * high; ++i) {
                const double middle = 0.5 * (low + high);
                (above(middle) > 0.0 ? low : high) = middle;
            }
            return 0.5 * (low + high);
        }
        t = next;
        previous = value;
    }
    return -1.0;
}

class TerrainAccuracy : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        Result<std::unique_ptr<GlContext>> created = GlContext::create({});
        ASSERT_TRUE(created) << created.error().message;
        context_ = std::move(created.value()).release();
        elevation_ = new AnalyticElevation();
        normals_ = new NormalMapSource("analytic.normals", elevation_, 1.0);
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

    static Camera camera(double latitude, double longitude, double aboveTerrain, double heading,
                         double pitch) {
        Camera c;
        c.geodetic = {latitude * kDegree, longitude * kDegree,
                      analyticHeight(latitude * kDegree, longitude * kDegree) + aboveTerrain};
        c.position = Ellipsoid::toEcef(c.geodetic);
        c.axes = Camera::axesFromAngles(c.geodetic, heading * kDegree, pitch * kDegree, 0.0);
        c.verticalFov = 60 * kDegree;
        return c;
    }

    static Image render(const Camera& c, int width, int height, bool atmosphere) {
        RenderSettings settings;
        settings.width = width;
        settings.height = height;
        settings.sunDirection = glm::normalize(c.position + c.axes[0] * 3.0e6 + c.axes[1] * 6.0e6);
        settings.atmosphere = atmosphere;
        settings.ocean = false;
        TerrainLayers layers{elevation_, nullptr, normals_, {}, {}};
        Result<Image> image = renderer_->render(layers, *evaluator_, c, settings);
        EXPECT_TRUE(image) << image.error().message;
        return image ? image.value() : Image{};
    }

    static GlContext* context_;
    static AnalyticElevation* elevation_;
    static NormalMapSource* normals_;
    static TileEvaluator* evaluator_;
    static SceneRenderer* renderer_;
};

GlContext* TerrainAccuracy::context_ = nullptr;
AnalyticElevation* TerrainAccuracy::elevation_ = nullptr;
NormalMapSource* TerrainAccuracy::normals_ = nullptr;
TileEvaluator* TerrainAccuracy::evaluator_ = nullptr;
SceneRenderer* TerrainAccuracy::renderer_ = nullptr;

struct DepthReport {
    double medianRelativeError = 0;
    int referenceHits = 0;
    // Sky where the reference hits terrain, and the reference also hits one pixel
    // higher: a hole inside the terrain.
    int holes = 0;
    // Sky where the reference hits only this pixel of its column's run: the true
    // silhouette lies within this pixel, and the coarse level that draws far terrain
    // (bilinear between band-limited samples) may pass below a grazed crest.
    int silhouetteMisses = 0;
};

DepthReport compareDepth(const Camera& c, const std::vector<float>& depth, double near, int width,
                         int height) {
    const double tanHalf = std::tan(c.verticalFov / 2);
    const double aspect = double(width) / height;
    const double maxDistance = 600e3;
    std::vector<double> errors;
    DepthReport report;
    std::vector<double> reference(std::size_t(width) * height, -1.0);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const glm::dvec3 view(((x + 0.5) / width * 2 - 1) * tanHalf * aspect,
                                  (1 - (y + 0.5) / height * 2) * tanHalf, -1.0);
            reference[std::size_t(y) * width + x] =
                rayCast(c.position, c.axes * glm::normalize(view), maxDistance);
        }
    }
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const double hit = reference[std::size_t(y) * width + x];
            if (hit < 0.0) {
                continue;
            }
            ++report.referenceHits;
            const float d = depth[std::size_t(y) * width + x];
            if (d <= 0.0f) {
                const bool interior = y > 0 && reference[std::size_t(y - 1) * width + x] >= 0.0;
                ++(interior ? report.holes : report.silhouetteMisses);
                continue;
            }
            const glm::dvec3 view(((x + 0.5) / width * 2 - 1) * tanHalf * aspect,
                                  (1 - (y + 0.5) / height * 2) * tanHalf, -1.0);
            const double rendered = (near / d) / -glm::normalize(view).z;
            errors.push_back(std::abs(rendered - hit) / hit);
        }
    }
    if (!errors.empty()) {
        std::nth_element(errors.begin(), errors.begin() + errors.size() / 2, errors.end());
        report.medianRelativeError = errors[errors.size() / 2];
    }
    return report;
}

TEST_F(TerrainAccuracy, DepthMatchesARayCastOfTheTrueSurface) {
    struct Case {
        const char* name;
        double latitude, longitude, above, heading, pitch;
    };
    const Case cases[] = {
        {"walker", 45.0, 7.0, 1.7, 30.0, -4.0},
        {"aircraft", 45.0, 7.0, 3000.0, 120.0, -25.0},
        {"high", -30.0, 179.9, 150e3, 10.0, -55.0},
        {"pole", 89.95, 40.0, 500.0, 180.0, -15.0},
    };
    constexpr int kWidth = 160, kHeight = 90;
    for (const Case& test : cases) {
        const Camera c =
            camera(test.latitude, test.longitude, test.above, test.heading, test.pitch);
        const Image image = render(c, kWidth, kHeight, false);
        ASSERT_FALSE(image.pixels.empty()) << test.name;
        const DepthReport report =
            compareDepth(c, renderer_->depth(), renderer_->near(), kWidth, kHeight);
        std::printf(
            "%-8s median relative depth error %.5f, %d terrain pixels, %d silhouette misses\n",
            test.name, report.medianRelativeError, report.referenceHits, report.silhouetteMisses);
        EXPECT_GT(report.referenceHits, kWidth * kHeight / 5) << test.name;
        EXPECT_LE(report.medianRelativeError, 0.005) << test.name;
        EXPECT_EQ(report.holes, 0)
            << test.name << ": " << report.holes << " of " << report.referenceHits << " pixels";
        // At most one pixel row of the silhouette may differ.
        EXPECT_LE(report.silhouetteMisses, kWidth) << test.name;
    }
}

double rmse(const Image& a, const Image& b) {
    double sum = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) {
        if (i % 4 != 3) {
            const double d = double(a.pixels[i]) - double(b.pixels[i]);
            sum += d * d;
        }
    }
    return std::sqrt(sum / (double(a.pixels.size()) * 0.75));
}

// Moving the eye by 1 cm must not make the terrain jump: with float world positions
// at 6,400 km from the centre the image would shake by ~0.5 m.
TEST_F(TerrainAccuracy, OneCentimetreMoveChangesTheImageOnlySlightly) {
    struct Case {
        const char* name;
        double latitude, longitude;
    };
    for (const Case& test :
         {Case{"mid-latitude", 45.0, 7.0}, Case{"north pole", 89.9999, 0.0},
          Case{"south pole", -89.9999, 123.0}, Case{"antimeridian", -12.0, 179.9999999}}) {
        const Camera a = camera(test.latitude, test.longitude, 1.7, 60.0, -8.0);
        Camera b = a;
        b.position += a.axes[0] * 0.01;  // 1 cm to the right
        b.geodetic = Ellipsoid::toGeodetic(b.position);
        const Image first = render(a, 160, 90, true);
        const Image second = render(b, 160, 90, true);
        ASSERT_EQ(first.pixels.size(), second.pixels.size());
        EXPECT_LT(rmse(first, second), 1.5) << test.name;
    }
    // On an 8,000 m high plateau the same holds (heights add to the float offsets).
    AnalyticElevation high(7600.0);
    NormalMapSource highNormals("high.normals", &high, 1.0);
    Camera a = camera(27.98, 86.92, 1.7 + 7600.0, 200.0, -6.0);
    Camera b = a;
    b.position += a.axes[0] * 0.01;
    b.geodetic = Ellipsoid::toGeodetic(b.position);
    RenderSettings settings;
    settings.width = 160;
    settings.height = 90;
    settings.sunDirection = glm::normalize(a.position + a.axes[0] * 3.0e6 + a.axes[1] * 6.0e6);
    settings.ocean = false;
    const TerrainLayers layers{&high, nullptr, &highNormals, {}, {}};
    Result<Image> first = renderer_->render(layers, *evaluator_, a, settings);
    Result<Image> second = renderer_->render(layers, *evaluator_, b, settings);
    ASSERT_TRUE(first && second);
    EXPECT_LT(rmse(first.value(), second.value()), 1.5) << "8,000 m plateau";
}

// From space the limb has no holes: the ring mesh's flat cells are chords of the
// curved surface (up to ~0.5 km below it at the limb from 1,800 km), so rays grazing
// the globe passed between them to the sky before the vertices were lifted by their
// cells' sagitta (the viewer bench's `frames_with_holes`, issue 20). A hole here is a
// sky pixel whose ray passes more than 50 m under the ellipsoid (made a sphere by
// scaling z) over a terrain at sea level.
TEST_F(TerrainAccuracy, TheLimbSeenFromSpaceHasNoHoles) {
    constexpr int kWidth = 320, kHeight = 180;
    const double altitude = 1800e3;
    // Pitched down by the horizon's dip, acos(R / (R + h)): the limb crosses the image.
    const double dip = std::acos(Ellipsoid::kMeanRadius / (Ellipsoid::kMeanRadius + altitude));
    Camera c = camera(45.0, 7.0, 0.0, 20.0, -dip / kDegree);
    c.geodetic.height = altitude;
    c.position = Ellipsoid::toEcef(c.geodetic);
    FlatElevation flat;
    NormalMapSource flatNormals("flat.normals", &flat, 1.0);
    RenderSettings settings;
    settings.width = kWidth;
    settings.height = kHeight;
    settings.sunDirection = glm::normalize(c.position);
    settings.atmosphere = false;
    settings.ocean = false;
    const TerrainLayers layers{&flat, nullptr, &flatNormals, {}, {}};
    ASSERT_TRUE(renderer_->render(layers, *evaluator_, c, settings));
    // Every ray points below the camera's horizon, so a line meeting the inner sphere meets
    // it ahead of the camera: the count's ray test is the line test this one made before.
    const FrameHoles count = FrameHoles::count(c, renderer_->depth(), kWidth, kHeight);
    const int deepRays = count.deepRays, holes = count.holes;
    EXPECT_GT(deepRays, kWidth * kHeight / 4);
    EXPECT_LT(deepRays, kWidth * kHeight * 3 / 4);  // the limb is in the picture
    EXPECT_EQ(holes, 0) << holes << " of " << deepRays << " rays under the surface show sky";
}

// The CPU elevation query gives the ground the GPU draws: a camera placed at 1.7 m
// above ElevationQuery::groundHeight and looking straight down sees the ground at
// 1.7 m (to a centimetre), anywhere, and the query is close to the true surface.
TEST_F(TerrainAccuracy, ElevationQueryMatchesTheDrawnGround) {
    for (const auto& [latitude, longitude] :
         {std::pair{45.0, 7.0}, std::pair{-33.3, -70.1}, std::pair{89.9999, 10.0},
          std::pair{1.0, 179.99999}}) {
        Camera c = camera(latitude, longitude, 1.7, 0.0, -90.0);
        const ElevationQuery query(*elevation_, *evaluator_);
        const LevelRange levels = renderer_->terrain().visibleLevels(c, 1.7, 90);
        Result<double> ground =
            query.groundHeight(c.geodetic.latitude, c.geodetic.longitude, levels.finest);
        ASSERT_TRUE(ground) << ground.error().message;
        EXPECT_NEAR(ground.value(), analyticHeight(c.geodetic.latitude, c.geodetic.longitude),
                    0.05);
        c.geodetic.height = ground.value() + 1.7;
        c.position = Ellipsoid::toEcef(c.geodetic);
        const Image image = render(c, 160, 90, false);
        ASSERT_FALSE(image.pixels.empty());
        const std::vector<float> depth = renderer_->depth();
        // The four pixels around the image centre straddle the view axis.
        double distance = 0;
        for (int y : {44, 45}) {
            for (int x : {79, 80}) {
                distance += renderer_->near() / depth[std::size_t(y) * 160 + x] / 4;
            }
        }
        EXPECT_NEAR(distance, 1.7, 0.01) << latitude << " " << longitude;
    }
}

}  // namespace
}  // namespace sylva::render
