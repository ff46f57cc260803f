// Golden images at 320x180 on llvmpipe: the demo project's three views (space,
// aircraft, ground) and the extremes fixtures (poles, antimeridian), plus a hole test
// against an analytic ray cast of the ellipsoid.
//
// Compared by RMSE and maximum channel error (llvmpipe is deterministic on one Mesa
// version; the tolerance absorbs small driver changes). On failure the actual image
// and a difference image are written to build/test-output/. Regenerate the goldens
// only with `make goldens` (SYLVA_UPDATE_GOLDENS=1), then look at them.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <string>

#include "GoldenImage.h"
#include "sylva/core/geo/Ellipsoid.h"
#include "sylva/core/image/ImageWriter.h"
#include "sylva/core/model/BlockReader.h"
#include "sylva/core/scheduler/TileEvaluator.h"
#include "sylva/core/terrain/ElevationQuery.h"
#include "sylva/core/terrain/LevelVisibility.h"
#include "sylva/dsl/ProjectLoader.h"
#include "sylva/render/batch/RenderSetup.h"
#include "sylva/render/gl/GlContext.h"
#include "sylva/render/scene/SceneRenderer.h"

namespace sylva::render {
namespace {

constexpr int kWidth = 320;
constexpr int kHeight = 180;

class ProjectGolden : public ::testing::Test {
protected:
    static void open(const std::string& projectPath, const std::string& goldenPrefix) {
        prefix_ = goldenPrefix;
        Result<std::unique_ptr<GlContext>> created = GlContext::create({});
        ASSERT_TRUE(created) << created.error().message;
        context_ = std::move(created.value()).release();
        dsl::LoadResult loaded = dsl::loadProject(projectPath);
        ASSERT_FALSE(loaded.hasErrors()) << loaded.render();
        model_ = new ProjectModel(std::move(*loaded.model));
        Result<SourceGraph> graph = SourceGraph::build(*model_);
        ASSERT_TRUE(graph) << graph.error().message;
        graph_ = new SourceGraph(std::move(graph.value()));
        Result<TerrainLayers> layers = graph_->terrainLayers(*model_, "");
        ASSERT_TRUE(layers) << layers.error().message;
        layers_ = layers.value();
        evaluator_ = new TileEvaluator(TileFormat{256, 2});
        Result<std::unique_ptr<SceneRenderer>> renderer =
            SceneRenderer::create(ShaderLibrary(), TerrainSettings{});
        ASSERT_TRUE(renderer) << renderer.error().message;
        renderer_ = renderer.value().release();
    }
    static void close() {
        delete renderer_;
        delete evaluator_;
        delete graph_;
        delete model_;
        delete context_;
    }

    // Renders camera `name` of the demo with the demo's render settings.
    // `adjust` may change the settings for the camera (sun, atmosphere) before rendering.
    static Image render(const std::string& name, Camera* cameraOut = nullptr,
                        const std::function<void(RenderSettings&, const Camera&)>& adjust = {}) {
        Result<RenderSetup> setup = RenderSetup::fromModel(*model_, kWidth, kHeight);
        EXPECT_TRUE(setup) << setup.error().message;
        RenderSettings settings = setup.value().settings;
        const Block* cameraBlock = model_->findCamera(name);
        EXPECT_NE(cameraBlock, nullptr);
        const ElevationQuery query(*layers_.elevation, *evaluator_);
        Result<Camera> camera = Camera::fromBlock(
            *cameraBlock, [&](double latitude, double longitude) -> Result<double> {
                const LevelRange levels =
                    LevelVisibility::visibleLevels(1.7, 1.7, 9000, 1.0, kHeight, 24);
                Result<double> h = query.groundHeight(latitude, longitude, levels.finest);
                return h ? Result<double>(std::max(h.value(), 0.0)) : h;
            });
        EXPECT_TRUE(camera) << camera.error().message;
        if (cameraOut) {
            *cameraOut = camera.value();
        }
        if (adjust) {
            adjust(settings, camera.value());
        }
        Result<Image> image = renderer_->render(layers_, *evaluator_, camera.value(), settings);
        EXPECT_TRUE(image) << image.error().message;
        return image ? image.value() : Image{};
    }

    static void checkGolden(const std::string& name) {
        const Image image = render(name);
        golden::checkGolden(prefix_ + name, kWidth, kHeight, image.pixels);
    }
    static void checkGolden(const std::string& name, const std::string& golden,
                            const std::function<void(RenderSettings&, const Camera&)>& adjust) {
        const Image image = render(name, nullptr, adjust);
        golden::checkGolden(prefix_ + golden, kWidth, kHeight, image.pixels);
    }

    // No holes: every pixel whose ray hits the ellipsoid (shrunk by 2 km, more than
    // the deepest chord of the coarsest drawn ring) must show terrain. Catches
    // cracks between levels and missing rings.
    static void checkNoHoles(const std::string& name) {
        Camera camera;
        const Image image = render(name, &camera);
        ASSERT_FALSE(image.pixels.empty());
        const std::vector<float> depth = renderer_->depth();
        const double a = Ellipsoid::kSemiMajorAxis - 2000.0;
        const double b = Ellipsoid::kSemiMinorAxis - 2000.0;
        const double tanHalf = std::tan(camera.verticalFov / 2);
        const double aspect = double(kWidth) / kHeight;
        int hits = 0, holes = 0;
        for (int y = 0; y < kHeight; ++y) {
            for (int x = 0; x < kWidth; ++x) {
                const double ndcX = (x + 0.5) / kWidth * 2 - 1;
                const double ndcY = 1 - (y + 0.5) / kHeight * 2;
                const glm::dvec3 view(ndcX * tanHalf * aspect, ndcY * tanHalf, -1.0);
                const glm::dvec3 direction = glm::normalize(camera.axes * view);
                // Scale z so the ellipsoid becomes a sphere of radius a.
                const glm::dvec3 o(camera.position.x, camera.position.y, camera.position.z * a / b);
                const glm::dvec3 d =
                    glm::normalize(glm::dvec3(direction.x, direction.y, direction.z * a / b));
                const double B = glm::dot(o, d);
                const double C = glm::dot(o, o) - a * a;
                if (B * B - C > 0 && -B - std::sqrt(B * B - C) > 0) {
                    ++hits;
                    if (depth[std::size_t(y) * kWidth + x] <= 0.0f) {
                        ++holes;
                    }
                }
            }
        }
        EXPECT_GT(hits, kWidth * kHeight / 4) << name;
        EXPECT_EQ(holes, 0) << name << ": " << holes << " of " << hits << " pixels show no terrain";
    }

    static std::string prefix_;
    static GlContext* context_;
    static ProjectModel* model_;
    static SourceGraph* graph_;
    static TerrainLayers layers_;
    static TileEvaluator* evaluator_;
    static SceneRenderer* renderer_;
};

std::string ProjectGolden::prefix_;
GlContext* ProjectGolden::context_ = nullptr;
ProjectModel* ProjectGolden::model_ = nullptr;
SourceGraph* ProjectGolden::graph_ = nullptr;
TerrainLayers ProjectGolden::layers_;
TileEvaluator* ProjectGolden::evaluator_ = nullptr;
SceneRenderer* ProjectGolden::renderer_ = nullptr;

class DemoGolden : public ProjectGolden {
protected:
    static void SetUpTestSuite() {
        open(std::string(SYLVA_PROJECTS_DIR) + "/demo/demo.sylva", "demo_");
    }
    static void TearDownTestSuite() { close(); }
};

class NorthGolden : public ProjectGolden {
protected:
    static void SetUpTestSuite() {
        open(std::string(SYLVA_TEST_DATA_DIR) + "/render/golden/extremes_north.sylva", "extremes_");
    }
    static void TearDownTestSuite() { close(); }
};

class SouthGolden : public ProjectGolden {
protected:
    static void SetUpTestSuite() {
        open(std::string(SYLVA_TEST_DATA_DIR) + "/render/golden/extremes_south.sylva", "extremes_");
    }
    static void TearDownTestSuite() { close(); }
};

TEST_F(DemoGolden, Space) {
    checkGolden("space");
}
TEST_F(DemoGolden, Aircraft) {
    checkGolden("aircraft");
}
// The aircraft view with 8 km visibility (a hazy day; the project's default is 40 km,
// a clear day: DemoGolden.Aircraft).
TEST_F(DemoGolden, AircraftHazy) {
    checkGolden("aircraft", "aircraft_hazy", [](RenderSettings& settings, const Camera&) {
        settings.atmosphereParameters = AtmosphereParameters::fromVisibility(8000.0).value();
    });
}
// The aircraft view at dusk: the sun 3 degrees below the horizon straight ahead (metered
// exposure: the twilight sky and the dim relief must stay visible).
TEST_F(DemoGolden, AircraftDusk) {
    checkGolden("aircraft", "aircraft_dusk", [](RenderSettings& settings, const Camera& camera) {
        const glm::dvec3 up =
            Ellipsoid::surfaceNormal(camera.geodetic.latitude, camera.geodetic.longitude);
        const glm::dvec3 forward = camera.axes * glm::dvec3(0, 0, -1);
        const glm::dvec3 ahead = glm::normalize(forward - up * glm::dot(forward, up));
        const double elevation = -3.0 * 3.14159265358979 / 180.0;
        settings.sunDirection = ahead * std::cos(elevation) + up * std::sin(elevation);
    });
}
TEST_F(DemoGolden, Ground) {
    checkGolden("ground");
}
// Over the woods: drawn trees to the instance distance, the far-field canopy on the
// ridges beyond it (issue 21: forest silhouettes to the horizon).
TEST_F(DemoGolden, Lookout) {
    checkGolden("lookout");
}

TEST_F(DemoGolden, NoHolesFromSpace) {
    checkNoHoles("space");
}
TEST_F(DemoGolden, NoHolesFromTheAircraft) {
    checkNoHoles("aircraft");
}

TEST_F(NorthGolden, NorthPoleGround) {
    checkGolden("north_pole_ground");
}
TEST_F(NorthGolden, AntimeridianGround) {
    checkGolden("antimeridian_ground");
}
TEST_F(NorthGolden, AntimeridianSpace) {
    checkGolden("antimeridian_space");
}
TEST_F(NorthGolden, NoHolesAcrossTheAntimeridian) {
    checkNoHoles("antimeridian_space");
}
TEST_F(SouthGolden, SouthPoleGround) {
    checkGolden("south_pole_ground");
}
TEST_F(SouthGolden, SouthPoleAircraft) {
    checkGolden("south_pole_aircraft");
}
TEST_F(SouthGolden, NoHolesOverTheSouthPole) {
    checkNoHoles("south_pole_aircraft");
}

}  // namespace
}  // namespace sylva::render
