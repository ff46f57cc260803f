// CameraBlockEditor: a saved camera round-trips through the language (the block the
// editor writes, loaded and read by Camera::fromBlock, gives the same position within
// 1 mm and the same axes within 1e-9), comments elsewhere survive, an existing block of
// that name is replaced, the views list gains the camera once, and errors leave the
// text alone.
#include "sylva/dsl/CameraBlockEditor.h"

#include <gtest/gtest.h>

#include <numbers>

#include "sylva/dsl/ProjectLoader.h"

namespace sylva::dsl {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

const char* kProject =
    "# header comment\n"
    "source height : constant { height = 200m } # trailing comment\n"
    "scenario base { layers = [@height] }\n"
    "camera first {\n"
    "    position = geo(10deg, 20deg, 3km)\n"
    "    fov = 60deg\n"
    "}\n"
    "views photos {\n"
    "    cameras = [@first]\n"
    "}\n"
    "views empty {\n"
    "    output = \"{camera}.png\"\n"
    "}\n";

Camera someCamera(double heading) {
    Camera camera;
    camera.geodetic = {-33.123456789 * kDegree, 151.987654321 * kDegree, 1234.5678};
    camera.position = Ellipsoid::toEcef(camera.geodetic);
    camera.axes =
        Camera::axesFromAngles(camera.geodetic, heading * kDegree, -12.5 * kDegree, 3.0 * kDegree);
    camera.verticalFov = 47.0 * kDegree;
    return camera;
}

TEST(CameraBlockEditor, ASavedCameraLoadsBackAsTheSameCamera) {
    const Camera camera = someCamera(-135.0);
    Result<std::string> text =
        CameraBlockEditor::withCamera(kProject, "p.sylva", "saved", camera, "photos");
    ASSERT_TRUE(text) << text.error().message;
    EXPECT_NE(text->find("# header comment"), std::string::npos);
    EXPECT_NE(text->find("# trailing comment"), std::string::npos);
    EXPECT_NE(text->find("cameras = [@first, @saved]"), std::string::npos) << *text;
    LoadResult loaded = loadProjectFromString(*text, "p.sylva");
    ASSERT_FALSE(loaded.hasErrors()) << loaded.render() << *text;
    const Block* block = loaded.model->findCamera("saved");
    ASSERT_NE(block, nullptr);
    Result<Camera> read =
        Camera::fromBlock(*block, [](double, double) -> Result<double> { return 0.0; });
    ASSERT_TRUE(read) << read.error().message;
    EXPECT_LT(glm::length(read->position - camera.position), 1e-3);
    for (int axis = 0; axis < 3; ++axis) {
        EXPECT_LT(glm::length(read->axes[axis] - camera.axes[axis]), 1e-9);
    }
    EXPECT_NEAR(read->verticalFov, camera.verticalFov, 1e-9);
}

TEST(CameraBlockEditor, AnExistingBlockIsReplacedAndListedOnce) {
    Result<std::string> once =
        CameraBlockEditor::withCamera(kProject, "p.sylva", "first", someCamera(10.0), "photos");
    ASSERT_TRUE(once) << once.error().message;
    EXPECT_EQ(once->find("geo(10deg, 20deg, 3km)"), std::string::npos) << *once;
    EXPECT_EQ(once->find("camera first"), once->rfind("camera first"));
    EXPECT_NE(once->find("cameras = [@first]"), std::string::npos) << *once;
    Result<std::string> listed =
        CameraBlockEditor::withCamera(*once, "p.sylva", "other", someCamera(20.0), "empty");
    ASSERT_TRUE(listed) << listed.error().message;
    EXPECT_NE(listed->find("cameras = [@other]"), std::string::npos) << *listed;
    EXPECT_FALSE(loadProjectFromString(*listed, "p.sylva").hasErrors());
}

TEST(CameraBlockEditor, ErrorsNameTheFile) {
    Result<std::string> noViews =
        CameraBlockEditor::withCamera(kProject, "p.sylva", "x", someCamera(0.0), "missing");
    ASSERT_FALSE(noViews);
    EXPECT_EQ(noViews.error().message, "p.sylva: no views block 'missing' to list camera 'x' in");
    Result<std::string> badName =
        CameraBlockEditor::withCamera(kProject, "p.sylva", "9 lives", someCamera(0.0));
    ASSERT_FALSE(badName);
    EXPECT_EQ(badName.error().message,
              "p.sylva: '9 lives' is not a valid camera name (letters, digits, _)");
    Result<std::string> broken =
        CameraBlockEditor::withCamera("camera a { fov = }\n}", "p.sylva", "x", someCamera(0.0));
    ASSERT_FALSE(broken);
    EXPECT_NE(broken.error().message.find("p.sylva: cannot save camera 'x'"), std::string::npos)
        << broken.error().message;
}

}  // namespace
}  // namespace sylva::dsl
