// The `photo` block read for a photomontage (core/scene PhotoViewpoint): the photograph
// and its EXIF lens (written here with OpenImageIO), the checks that tie it to the camera,
// and camera matching from its control points — with the exact located messages of every
// bad input. References: the 35 mm frame's 39.60° for a 50 mm lens (36 mm wide, 3:2),
// control points projected from a known camera by the pinhole formula written out here.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include <unistd.h>

#include "sylva/core/scene/PhotoViewpoint.h"
#include "sylva/dsl/ProjectLoader.h"

namespace sylva {
namespace {

namespace fs = std::filesystem;
constexpr double kDegree = std::numbers::pi / 180.0;

fs::path folder() {
    const fs::path path = fs::temp_directory_path() / ("sylva-photo-" + std::to_string(::getpid()));
    fs::create_directories(path);
    return path;
}

// A grey JPEG of width × height with EXIF FocalLengthIn35mmFilm when `focal35` > 0.
void writePhoto(const fs::path& path, int width, int height, int focal35) {
    OIIO::ImageSpec spec(width, height, 3, OIIO::TypeDesc::UINT8);
    if (focal35 > 0) {
        spec.attribute("Exif:FocalLengthIn35mmFilm", focal35);
    }
    spec.attribute("Exif:DateTimeOriginal", "2024:09:15 08:30:00");
    std::vector<std::uint8_t> pixels(std::size_t(width) * height * 3, 128);
    auto out = OIIO::ImageOutput::create(path.string());
    ASSERT_TRUE(out && out->open(path.string(), spec));
    ASSERT_TRUE(out->write_image(OIIO::TypeDesc::UINT8, pixels.data()));
    out->close();
}

// The project text around `camera` attributes and `photo` attributes (line 1 is `camera`).
std::string project(const std::string& camera, const std::string& photo) {
    return "camera vp { position = geo(-7.96deg, -34.9deg, 120m); heading = 60deg; " + camera +
           " }\n"
           "source ground : constant { kind = elevation; height = 0m }\n"
           "scenario today { layers = [@ground] }\n"
           "scenario proposed extends today { }\n"
           "photo vp_photo {\n"
           "    camera = @vp; scenario = @proposed; baseline = @today\n" +
           photo + "\n}\n";
}

struct Loaded {
    ProjectModel model;
    fs::path file;
};

Loaded load(const std::string& text) {
    const fs::path file = folder() / "photo.sylva";
    std::ofstream(file) << text;
    dsl::LoadResult result = dsl::loadProject(file);
    EXPECT_EQ(result.render(), "");
    EXPECT_TRUE(result.model.has_value());
    return {result.model ? *result.model : ProjectModel{}, file};
}

Camera cameraOf(const ProjectModel& model) {
    const Block* block = model.findCamera("vp");
    EXPECT_NE(block, nullptr);
    Result<Camera> camera =
        Camera::fromBlock(*block, [](double, double) -> Result<double> { return 0.0; });
    EXPECT_TRUE(camera) << camera.error().message;
    return camera ? camera.value() : Camera{};
}

// Reads the block, the photograph and fits the camera: the first error, or "".
std::string fitError(const std::string& text, Camera* fitted = nullptr) {
    const Loaded loaded = load(text);
    Result<PhotoViewpoint> photo =
        PhotoViewpoint::fromBlock(loaded.model, loaded.model.photos.at(0));
    if (!photo) {
        return photo.error().message;
    }
    Result<Photo> picture = photo->readPhoto();
    if (!picture) {
        return picture.error().message;
    }
    Result<Camera> camera =
        photo->fitCamera(cameraOf(loaded.model), *loaded.model.findCamera("vp"), picture.value());
    if (!camera) {
        return camera.error().message;
    }
    if (fitted) {
        *fitted = camera.value();
    }
    Result<std::optional<CameraMatch>> match = photo->match(camera.value(), picture.value());
    return match ? "" : match.error().message;
}

TEST(PhotoViewpoint, MissingPhotographIsLocatedAtFile) {
    const std::string where = (folder() / "photo.sylva").string();
    EXPECT_EQ(fitError(project("", "    file = \"absent.jpg\"")),
              where + ":7:12: photo 'vp_photo': " + (folder() / "absent.jpg").string() +
                  ": the photograph does not exist");
}

TEST(PhotoViewpoint, UnreadablePhotographIsLocatedAtFile) {
    std::ofstream(folder() / "text.jpg") << "not a JPEG";
    const std::string message = fitError(project("", "    file = \"text.jpg\""));
    const std::string expected = (folder() / "photo.sylva").string() +
                                 ":7:12: photo 'vp_photo': " + (folder() / "text.jpg").string() +
                                 ": not a readable image";
    EXPECT_EQ(message.substr(0, expected.size()), expected) << message;
}

TEST(PhotoViewpoint, ExifLensGivesTheFieldOfView) {
    writePhoto(folder() / "exif50.jpg", 60, 40, 50);
    Camera camera;
    EXPECT_EQ(fitError(project("", "    file = \"exif50.jpg\""), &camera), "");
    // 50 mm (35 mm equivalent) on a 3:2 image: the 36 × 24 mm frame's 39.60° × 26.99°.
    EXPECT_NEAR(camera.horizontalFov / kDegree, 39.5978, 1e-3);
    EXPECT_NEAR(camera.fitted(60, 40).verticalFov / kDegree, 26.9915, 1e-3);
}

TEST(PhotoViewpoint, ExifLensThatDisagreesIsAnError) {
    writePhoto(folder() / "exif50b.jpg", 60, 40, 50);
    EXPECT_EQ(fitError(project("focal_length = 35mm", "    file = \"exif50b.jpg\"")),
              (folder() / "photo.sylva").string() +
                  ":7:12: photo 'vp_photo': the photograph's EXIF FocalLengthIn35mmFilm is 50.0 "
                  "mm but camera 'vp' has a 35 mm equivalent of 35.0 mm at 60 x 40 pixels; "
                  "remove the camera's field of view to use the EXIF lens, or correct it");
    // An agreeing lens passes.
    EXPECT_EQ(fitError(project("focal_length = 50mm", "    file = \"exif50b.jpg\"")), "");
}

TEST(PhotoViewpoint, PhotographOfAnotherAspectThanThePrintIsAnError) {
    writePhoto(folder() / "plain.jpg", 60, 40, 0);
    EXPECT_EQ(
        fitError(project("output_size = [820mm, 260mm]; dpi = 10", "    file = \"plain.jpg\"")),
        (folder() / "photo.sylva").string() +
            ":7:12: photo 'vp_photo': the photograph is 60 x 40 pixels (aspect 1.500) but "
            "camera 'vp' prints at aspect 3.154 (output_size); crop the photograph or "
            "change output_size");
}

TEST(PhotoViewpoint, ThreeControlPointsAreTooFew) {
    writePhoto(folder() / "plain3.jpg", 60, 40, 0);
    EXPECT_EQ(
        fitError(
            project("",
                    "    file = \"plain3.jpg\"\n    control_points = [\n"
                    "        { position = geo(-7.95deg, -34.89deg, 10m), pixel = [10px, 20px] },\n"
                    "        { position = geo(-7.95deg, -34.88deg, 10m), pixel = [30px, 20px] },\n"
                    "        { position = geo(-7.94deg, -34.89deg, 10m), pixel = [50px, 22px] }\n"
                    "    ]")),
        (folder() / "photo.sylva").string() +
            ":8:22: photo 'vp_photo': camera matching needs at least 4 control points, 3 given");
}

TEST(PhotoViewpoint, ControlPointWithoutHeightIsAnError) {
    writePhoto(folder() / "plain4.jpg", 60, 40, 0);
    EXPECT_EQ(
        fitError(project("",
                         "    file = \"plain4.jpg\"\n    control_points = [\n"
                         "        { position = geo(-7.95deg, -34.89deg), pixel = [10px, 20px] }\n"
                         "    ]")),
        (folder() / "photo.sylva").string() +
            ":9:9: photo 'vp_photo': a control point needs its surveyed height: geo(lat, "
            "lon, height)");
}

// A pinhole projection written out independently of ImageProjection: pixel of ECEF point
// `p` for a camera with axes (right, up, back) and vertical field `fov` on w × h.
glm::dvec2 pinhole(const Camera& camera, const glm::dvec3& p, int w, int h) {
    const glm::dvec3 d = p - camera.position;
    const double x = glm::dot(d, camera.axes[0]), y = glm::dot(d, camera.axes[1]),
                 z = -glm::dot(d, camera.axes[2]);
    const double f = (h / 2.0) / std::tan(camera.verticalFov / 2.0);
    return {w / 2.0 + f * x / z, h / 2.0 - f * y / z};
}

TEST(PhotoViewpoint, ControlPointsSolveTheCamera) {
    writePhoto(folder() / "match.jpg", 600, 400, 50);
    // The true camera looks 1.5° further right and 0.8° higher than the block's guess.
    Camera truth;
    truth.geodetic = {-7.96 * kDegree, -34.9 * kDegree, 120.0};
    truth.position = Ellipsoid::toEcef(truth.geodetic);
    truth.axes = Camera::axesFromAngles(truth.geodetic, 61.5 * kDegree, 0.8 * kDegree, 0.0);
    truth.verticalFov = 2.0 * std::atan(12.0 / 50.0);
    const double points[6][3] = {{-7.95535, -34.89444, 40}, {-7.95629, -34.88977, 15},
                                 {-7.95548, -34.89214, 90}, {-7.95836, -34.89387, 60},
                                 {-7.95222, -34.88885, 25}, {-7.95656, -34.89260, 5}};
    std::string list;
    for (const auto& p : points) {
        const glm::dvec3 ecef = Ellipsoid::toEcef({p[0] * kDegree, p[1] * kDegree, p[2]});
        const glm::dvec2 pixel = pinhole(truth, ecef, 600, 400);
        ASSERT_TRUE(pixel.x > 0 && pixel.x < 600 && pixel.y > 0 && pixel.y < 400) << p[0];
        char text[160];
        std::snprintf(
            text, sizeof text,
            "        { position = geo(%.5fdeg, %.5fdeg, %.0fm), pixel = [%.3fpx, %.3fpx] },\n",
            p[0], p[1], p[2], pixel.x, pixel.y);
        list += text;
    }
    const Loaded loaded =
        load(project("", "    file = \"match.jpg\"\n    control_points = [\n" + list + "    ]"));
    Result<PhotoViewpoint> photo =
        PhotoViewpoint::fromBlock(loaded.model, loaded.model.photos.at(0));
    ASSERT_TRUE(photo) << photo.error().message;
    Result<Photo> picture = photo->readPhoto();
    ASSERT_TRUE(picture) << picture.error().message;
    EXPECT_EQ(picture->exif.dateTimeOriginal, "2024:09:15 08:30:00");
    Result<Camera> fitted =
        photo->fitCamera(cameraOf(loaded.model), *loaded.model.findCamera("vp"), picture.value());
    ASSERT_TRUE(fitted) << fitted.error().message;
    Result<std::optional<CameraMatch>> match = photo->match(fitted.value(), picture.value());
    ASSERT_TRUE(match) << match.error().message;
    ASSERT_TRUE(match->has_value());
    const Camera& solved = (*match)->camera;
    EXPECT_NEAR(solved.heading() / kDegree, 61.5, 0.01);
    EXPECT_NEAR(solved.pitch() / kDegree, 0.8, 0.01);
    EXPECT_LT((*match)->rms, 0.01);
}

}  // namespace
}  // namespace sylva
