// The example program (examples/render_project.cpp) renders the demo's space view through
// the library API (sylva_dsl + render::BatchRenderer), as a separate process exactly as a
// user would run it; its image must match the demo's golden (the one DemoGolden.Space
// renders through SceneRenderer directly) under the shared tolerant comparison, so the
// test fails if the example renders another view, another size or nothing.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "GoldenImage.h"
#include "sylva/core/image/ImageWriter.h"

namespace sylva {
namespace {

std::string quoted(const std::filesystem::path& path) {
    std::string text = "'";
    return text.append(path.string()).append("'");
}

TEST(ExampleProgram, RendersTheDemoSpaceViewThroughTheLibrary) {
    if (golden::updatingGoldens()) {
        GTEST_SKIP() << "the demo goldens come from DemoGolden; nothing to update here";
    }
    const std::filesystem::path out =
        std::filesystem::path(SYLVA_TEST_OUTPUT_DIR) / "example-render-project";
    std::filesystem::remove_all(out);
    std::filesystem::create_directories(out);
    const std::filesystem::path log = out / "log.txt";
    // Appended piecewise: GCC 12's -Wrestrict misfires on chains of `+`.
    std::string command = quoted(SYLVA_EXAMPLE_RENDER_PROJECT);
    command.append(" ")
        .append(quoted(std::filesystem::path(SYLVA_PROJECTS_DIR) / "demo" / "demo.sylva"))
        .append(" space ")
        .append(quoted(out / "images"))
        .append(" 320x180 >")
        .append(quoted(log))
        .append(" 2>&1");
    const int status = std::system(command.c_str());
    std::ifstream stream(log);
    std::stringstream text;
    text << stream.rdbuf();
    ASSERT_EQ(status, 0) << command << "\n" << text.str();
    const std::filesystem::path image = out / "images" / "space.png";
    const std::string line = std::string(image.string()).append("  320x180");
    EXPECT_NE(text.str().find(line), std::string::npos) << text.str();
    int width = 0, height = 0;
    Result<std::vector<std::uint8_t>> pixels = ImageWriter::readRgba8(image, width, height);
    ASSERT_TRUE(pixels) << pixels.error().message;
    golden::expectMatchesGolden("demo_space", width, height, pixels.value());
    // The example renders exactly the one job asked for.
    std::size_t files = 0;
    for (const auto& entry : std::filesystem::recursive_directory_iterator(out / "images")) {
        files += entry.is_regular_file() ? 1 : 0;
    }
    EXPECT_EQ(files, 1u);
}

}  // namespace
}  // namespace sylva
