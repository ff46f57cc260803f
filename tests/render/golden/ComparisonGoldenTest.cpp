// Comparison images through the renderer: two scenarios of a small synthetic project
// (noise terrain; the second scenario drier and with a raised plateau) rendered at
// 320x180, then blend, side_by_side, swipe and difference against golden PNGs
// (`make goldens` rewrites them). The same renders check the linear read-back for EXR
// output: the radiance tone-maps to the 8-bit image, an EXR written and read back
// through OpenImageIO is half float with its metadata, and a linear swipe displays as
// the 8-bit swipe of the displayed images.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "GoldenImage.h"
#include "sylva/core/geo/Ellipsoid.h"
#include "sylva/core/image/ImageComparison.h"
#include "sylva/core/image/ImageWriter.h"
#include "sylva/core/image/ToneMapping.h"
#include "sylva/core/scheduler/TileEvaluator.h"
#include "sylva/dsl/ProjectLoader.h"
#include "sylva/render/gl/GlContext.h"
#include "sylva/render/scene/SceneRenderer.h"

namespace sylva::render {
namespace {

constexpr int kWidth = 320;
constexpr int kHeight = 180;
constexpr double kDegree = 3.14159265358979323846 / 180.0;

constexpr const char* kProject = R"(
source height : noise { seed = 3; octaves = 8; amplitude = 1500m; base_wavelength = 400km }
source ground : hypsometric { height = @height }
source raised : noise { seed = 3; octaves = 8; amplitude = 2500m; base_wavelength = 400km }
source raised_ground : hypsometric { height = @raised }
source dry : adjust { input = @raised_ground; saturation = 0.3; brightness = 0.04 }
scenario today { layers = [@height, @ground] }
scenario drought { layers = [@raised, @dry] }
camera coast { position = geo(20deg, 10deg, 30km); pitch = -30deg; fov = 60deg }
)";

struct Renders {
    Image today, drought;
};

// Renders the camera in both scenarios (once per test binary).
const Renders& renders() {
    static Renders result = [] {
        Renders out;
        Result<std::unique_ptr<GlContext>> context = GlContext::create({});
        EXPECT_TRUE(context) << context.error().message;
        if (!context) {
            return out;
        }
        dsl::LoadResult loaded = dsl::loadProjectFromString(kProject, "comparison.sylva");
        EXPECT_FALSE(loaded.hasErrors()) << loaded.render();
        if (loaded.hasErrors()) {
            return out;
        }
        Result<std::unique_ptr<SceneRenderer>> renderer =
            SceneRenderer::create(ShaderLibrary(), TerrainSettings{});
        EXPECT_TRUE(renderer) << renderer.error().message;
        TileEvaluator evaluator(TileFormat{256, 2});
        RenderSettings settings;
        settings.width = kWidth;
        settings.height = kHeight;
        settings.sunDirection = Ellipsoid::surfaceNormal(20 * kDegree, 11 * kDegree);
        settings.exposure = 0.8;
        settings.linearOutput = true;
        for (const char* name : {"today", "drought"}) {
            const ProjectModel* model = loaded.modelFor(name);
            Result<SourceGraph> graph = SourceGraph::build(*model);
            EXPECT_TRUE(graph) << graph.error().message;
            Result<TerrainLayers> layers = graph.value().terrainLayers(*model, name);
            EXPECT_TRUE(layers) << layers.error().message;
            Result<Camera> camera = Camera::fromBlock(*model->findCamera("coast"), {});
            EXPECT_TRUE(camera) << camera.error().message;
            Result<Image> image =
                renderer.value()->render(layers.value(), evaluator, camera.value(), settings);
            EXPECT_TRUE(image) << image.error().message;
            (std::string(name) == "today" ? out.today : out.drought) = image.value();
        }
        renderer.value().reset();
        return out;
    }();
    return result;
}

RgbaImage rgba(const Image& image) {
    RgbaImage out;
    out.width = image.width;
    out.height = image.height;
    out.pixels = image.pixels;
    return out;
}

LinearImage linear(const Image& image) {
    LinearImage out;
    out.width = image.width;
    out.height = image.height;
    out.pixels = image.radiance;
    return out;
}

// The comparison goldens are tests/render/goldens/comparison_<name>.png.
void checkGolden(const RgbaImage& image, const std::string& name) {
    golden::checkGolden("comparison_" + name, image.width, image.height, image.pixels);
}

TEST(ComparisonGolden, Blend) {
    Result<RgbaImage> made =
        ImageComparison::blend(rgba(renders().today), rgba(renders().drought), 0.5);
    ASSERT_TRUE(made) << made.error().message;
    checkGolden(made.value(), "blend");
}

TEST(ComparisonGolden, SideBySide) {
    Result<RgbaImage> made =
        ImageComparison::sideBySide(rgba(renders().today), rgba(renders().drought));
    ASSERT_TRUE(made) << made.error().message;
    ImageComparison::label(made.value(), "today");
    ImageComparison::label(made.value(), "drought", true);
    checkGolden(made.value(), "side_by_side");
}

TEST(ComparisonGolden, Swipe) {
    Result<RgbaImage> made =
        ImageComparison::swipe(rgba(renders().today), rgba(renders().drought), 0.4);
    ASSERT_TRUE(made) << made.error().message;
    ImageComparison::label(made.value(), "today");
    ImageComparison::label(made.value(), "drought", true);
    checkGolden(made.value(), "swipe");
}

TEST(ComparisonGolden, Difference) {
    Result<RgbaImage> made =
        ImageComparison::difference(rgba(renders().today), rgba(renders().drought));
    ASSERT_TRUE(made) << made.error().message;
    checkGolden(made.value(), "difference");
}

// The linear read-back is the radiance the 8-bit image was tone-mapped from.
TEST(LinearOutput, RadianceToneMapsToTheSrgbImage) {
    const Image& image = renders().today;
    ASSERT_EQ(image.radiance.size(), image.pixels.size());
    const RgbaImage displayed = ToneMapping::display(linear(image));
    int maxError = 0;
    double maxRadiance = 0;
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
        if (i % 4 != 3) {
            maxError =
                std::max(maxError, std::abs(int(displayed.pixels[i]) - int(image.pixels[i])));
            maxRadiance = std::max(maxRadiance, double(image.radiance[i]));
        }
    }
    EXPECT_LE(maxError, 1);       // float rounding on the GPU vs the CPU
    EXPECT_GT(maxRadiance, 0.1);  // a lit scene, not an empty target
}

TEST(LinearOutput, ExrRoundTripIsHalfFloatWithMetadata) {
    const Image& image = renders().drought;
    const std::filesystem::path file = std::filesystem::path(SYLVA_TEST_OUTPUT_DIR) / "linear.exr";
    ImageMetadata metadata;
    metadata.set("sylva:scenario", "drought");
    metadata.set("sylva:camera", "valley");
    metadata.set("sylva:time", "2024-06-21T09:00:00-03:00");
    ASSERT_TRUE(ImageWriter::writeLinear(file, linear(image), metadata));

    std::unique_ptr<OIIO::ImageInput> input = OIIO::ImageInput::open(file.string());
    ASSERT_TRUE(input) << OIIO::geterror();
    const OIIO::ImageSpec& spec = input->spec();
    EXPECT_EQ(spec.format, OIIO::TypeDesc::HALF);
    EXPECT_EQ(spec.nchannels, 4);
    EXPECT_EQ(spec.width, kWidth);
    EXPECT_EQ(spec.get_string_attribute("sylva:scenario"), "drought");
    EXPECT_EQ(spec.get_string_attribute("sylva:camera"), "valley");
    EXPECT_EQ(spec.get_string_attribute("sylva:time"), "2024-06-21T09:00:00-03:00");
    std::vector<float> values(std::size_t(kWidth) * kHeight * 4);
    ASSERT_TRUE(input->read_image(0, 0, 0, 4, OIIO::TypeDesc::FLOAT, values.data()));
    LinearImage read(kWidth, kHeight);
    read.pixels = values;
    const RgbaImage displayed = ToneMapping::display(read);
    int maxError = 0;
    for (std::size_t i = 0; i < values.size(); ++i) {
        if (i % 4 != 3) {
            // Half keeps 11 significant bits: within 0.1 % of the float radiance.
            EXPECT_NEAR(values[i], image.radiance[i], 1e-3 * std::abs(image.radiance[i]) + 1e-6);
            maxError =
                std::max(maxError, std::abs(int(displayed.pixels[i]) - int(image.pixels[i])));
        }
    }
    EXPECT_LE(maxError, 1);
}

TEST(LinearOutput, LinearComparisonsDisplayAsTheirSrgbTwins) {
    const LinearImage today = linear(renders().today);
    const LinearImage drought = linear(renders().drought);
    auto maxError = [](const RgbaImage& a, const RgbaImage& b) {
        int error = 0;
        for (std::size_t i = 0; i < a.pixels.size(); ++i) {
            error = std::max(error, std::abs(int(a.pixels[i]) - int(b.pixels[i])));
        }
        return error;
    };
    Result<LinearImage> swipe = ImageComparison::swipe(today, drought, 0.4);
    ASSERT_TRUE(swipe);
    ImageComparison::label(swipe.value(), "today");
    Result<RgbaImage> swipe8 =
        ImageComparison::swipe(ToneMapping::display(today), ToneMapping::display(drought), 0.4);
    ImageComparison::label(swipe8.value(), "today");
    EXPECT_LE(maxError(ToneMapping::display(swipe.value()), swipe8.value()), 1);

    Result<LinearImage> difference = ImageComparison::difference(today, drought);
    ASSERT_TRUE(difference);
    Result<RgbaImage> difference8 =
        ImageComparison::difference(ToneMapping::display(today), ToneMapping::display(drought));
    EXPECT_LE(maxError(ToneMapping::display(difference.value()), difference8.value()), 1);

    // Blend mixes radiance: at 50 % exactly the mean of the two.
    Result<LinearImage> blend = ImageComparison::blend(today, drought, 0.5);
    ASSERT_TRUE(blend);
    for (std::size_t i = 0; i < blend.value().pixels.size(); i += 97) {
        EXPECT_FLOAT_EQ(blend.value().pixels[i], 0.5f * (today.pixels[i] + drought.pixels[i]));
    }
}

}  // namespace
}  // namespace sylva::render
