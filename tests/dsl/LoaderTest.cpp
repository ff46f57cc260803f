// Valid projects produce the expected model; file-level failures are diagnostics.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <string>

#include "sylva/dsl/ProjectLoader.h"

namespace sylva::dsl {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
const std::string kDemo = std::string(SYLVA_TEST_DATA_DIR) + "/dsl/cases/demo.sylva";

double quantityOf(const Block& block, const std::string& name) {
    const Attribute* attribute = block.find(name);
    EXPECT_NE(attribute, nullptr) << name;
    if (!attribute || !attribute->value.get<Quantity>()) {
        return NAN;
    }
    return attribute->value.get<Quantity>()->value;
}

TEST(Loader, DemoProjectLoadsClean) {
    LoadResult result = loadProject(kDemo);
    EXPECT_EQ(result.render(), "");
    ASSERT_TRUE(result.model.has_value());
    const ProjectModel& model = *result.model;
    EXPECT_EQ(model.project.find("title")->value.get<std::string>()[0], "Demo");
    EXPECT_EQ(model.scenario, "earth");
    ASSERT_EQ(model.sources.size(), 3u);
    ASSERT_EQ(model.cameras.size(), 2u);
    ASSERT_EQ(model.views.size(), 1u);

    const Block* height = model.findSource("height");
    ASSERT_NE(height, nullptr);
    EXPECT_EQ(height->kind, "noise");
    EXPECT_DOUBLE_EQ(quantityOf(*height, "amplitude"), 2500.0);  // @relief substituted
    EXPECT_DOUBLE_EQ(quantityOf(*height, "seed"), 7.0);
    EXPECT_DOUBLE_EQ(quantityOf(*height, "octaves"), 24.0);  // default filled
    EXPECT_EQ(height->find("octaves")->location.line, 3u);

    const Reference* normalsHeight =
        model.findSource("normals")->find("height")->value.get<Reference>();
    ASSERT_NE(normalsHeight, nullptr);
    EXPECT_EQ(normalsHeight->kind, "source");
    EXPECT_EQ(normalsHeight->name, "height");

    const ValueList* layers = model.findScenario("earth")->find("layers")->value.get<ValueList>();
    ASSERT_NE(layers, nullptr);
    ASSERT_EQ(layers->size(), 3u);
    EXPECT_EQ((*layers)[1].get<Reference>()->name, "colour");

    const GeoPosition* space =
        model.findCamera("space")->find("position")->value.get<GeoPosition>();
    ASSERT_NE(space, nullptr);
    EXPECT_NEAR(space->latitude, 20 * kDegree, 1e-12);
    EXPECT_NEAR(space->longitude, 10 * kDegree, 1e-12);
    ASSERT_TRUE(space->height.has_value());
    EXPECT_DOUBLE_EQ(*space->height, 800000.0);
    const Block* ground = model.findCamera("ground");
    EXPECT_FALSE(ground->find("position")->value.get<GeoPosition>()->height.has_value());
    EXPECT_DOUBLE_EQ(quantityOf(*ground, "eye_height"), 1.7);
    EXPECT_NEAR(quantityOf(*ground, "pitch"), -2 * kDegree, 1e-12);
    // No field of view written: none in the model (Camera::fromBlock uses 60° vertical).
    EXPECT_EQ(ground->find("fov"), nullptr);

    const ValueList* resolution = model.render.find("resolution")->value.get<ValueList>();
    ASSERT_NE(resolution, nullptr);
    EXPECT_DOUBLE_EQ((*resolution)[0].get<Quantity>()->value, 320.0);
    EXPECT_EQ((*resolution)[0].get<Quantity>()->dimension, Dimension::Pixels);
    EXPECT_EQ(model.render.find("atmosphere")->value.get<bool>()[0], true);

    ASSERT_EQ(model.params.size(), 1u);
    EXPECT_EQ(model.params[0].name, "relief");
    EXPECT_DOUBLE_EQ(model.params[0].find("value")->value.get<Quantity>()->value, 2500.0);
}

TEST(Loader, DefineOverridesParam) {
    LoadOptions options;
    options.defines = {{"relief", "1.2km + 300m"}};
    LoadResult result = loadProject(kDemo, options);
    ASSERT_TRUE(result.model.has_value()) << result.render();
    EXPECT_DOUBLE_EQ(quantityOf(*result.model->findSource("height"), "amplitude"), 1500.0);
    EXPECT_DOUBLE_EQ(result.model->params[0].find("value")->value.get<Quantity>()->value, 1500.0);
}

TEST(Loader, MissingProjectAndRenderGetDefaults) {
    LoadResult result = loadProjectFromString("", "empty.sylva");
    EXPECT_EQ(result.render(), "");
    ASSERT_TRUE(result.model.has_value());
    EXPECT_EQ(result.model->project.keyword, "project");
    EXPECT_NE(result.model->project.find("title"), nullptr);
    EXPECT_EQ(result.model->render.keyword, "render");
    EXPECT_NE(result.model->render.find("resolution"), nullptr);
    EXPECT_DOUBLE_EQ(quantityOf(result.model->render, "exposure"), 1.0);
}

TEST(Loader, LexicalForms) {
    const char* text = R"(
# comment
// comment
/* nested /* comment */ still */
project { title = "a\"b\\c\nd" }
/- render { exposure = "ignored" }
render {
    /- exposure = "ignored"
    exposure = (2 + 4) / 2 * 50%
    resolution = [
        2 * 160px,
        90px + 90px,
    ]
}
source c : hypsometric { height = @n; rock = #FF800080 }
source n : noise { ridges = 25%; offset = -(10m - 2cm) ; base_wavelength = 1000km }
)";
    LoadResult result = loadProjectFromString(text, "lex.sylva");
    ASSERT_TRUE(result.model.has_value()) << result.render();
    EXPECT_EQ(result.render(), "");
    const ProjectModel& model = *result.model;
    EXPECT_EQ(*model.project.find("title")->value.get<std::string>(), "a\"b\\c\nd");
    EXPECT_DOUBLE_EQ(quantityOf(model.render, "exposure"), 1.5);
    const ValueList* resolution = model.render.find("resolution")->value.get<ValueList>();
    EXPECT_DOUBLE_EQ((*resolution)[1].get<Quantity>()->value, 180.0);
    const Color* rock = model.findSource("c")->find("rock")->value.get<Color>();
    ASSERT_NE(rock, nullptr);
    EXPECT_FLOAT_EQ(rock->r, 1.0f);
    EXPECT_FLOAT_EQ(rock->g, 128.0f / 255.0f);
    EXPECT_FLOAT_EQ(rock->a, 128.0f / 255.0f);
    EXPECT_DOUBLE_EQ(quantityOf(*model.findSource("n"), "ridges"), 0.25);
    EXPECT_DOUBLE_EQ(quantityOf(*model.findSource("n"), "offset"), -9.98);
    EXPECT_DOUBLE_EQ(quantityOf(*model.findSource("n"), "base_wavelength"), 1.0e6);
}

TEST(Loader, MissingFile) {
    LoadResult result = loadProject("no/such/project.sylva");
    EXPECT_FALSE(result.model.has_value());
    EXPECT_EQ(result.render(), "error[E0001]: cannot read 'no/such/project.sylva': no such file\n");
}

TEST(Loader, Directory) {
    LoadResult result = loadProject(std::string(SYLVA_TEST_DATA_DIR) + "/dsl");
    EXPECT_TRUE(result.hasErrors());
    EXPECT_EQ(result.render(), "error[E0001]: cannot read '" + std::string(SYLVA_TEST_DATA_DIR) +
                                   "/dsl': it is a directory\n");
}

TEST(Loader, BinaryGarbage) {
    std::string garbage(
        "\x7f"
        "ELF\x02\x01\x01\x00\x00\xff\xfe\x80",
        13);
    LoadResult result = loadProjectFromString(garbage, "garbage.bin");
    EXPECT_FALSE(result.model.has_value());
    EXPECT_EQ(result.render(),
              "error[E0003]: cannot read 'garbage.bin': not valid UTF-8 (byte 0xFF at line 1, "
              "column 10)\n");
}

TEST(Loader, ControlCharactersInValidUtf8) {
    std::string text("project {}\n\x01\x02\x03\n", 15);
    EXPECT_EQ(loadProjectFromString(text, "ctl.sylva").render(),
              "error[E0004]: unexpected characters starting with '\\x01'\n"
              " --> ctl.sylva:2:1\n"
              "  |\n"
              "2 | \x01\x02\x03\n"
              "  | ^^^ not part of the language here\n");
}

TEST(Loader, TooLarge) {
    std::string big(kMaxProjectFileBytes + 1, ' ');
    EXPECT_EQ(loadProjectFromString(big, "big.sylva").render(),
              "error[E0002]: cannot read 'big.sylva': file is 16777217 bytes, over the 16 MiB "
              "limit\n");
}

TEST(Loader, RecoveryReportsEveryBrokenStatement) {
    const char* text =
        "project {\n    title = \n    description = 3 4\n}\nrender { exposure = (1 + ) }\n}\n";
    LoadResult result = loadProjectFromString(text, "r.sylva");
    ASSERT_EQ(result.diagnostics.size(), 4u) << result.render();
    EXPECT_EQ(result.diagnostics[0].location.line, 2u);
    EXPECT_EQ(result.diagnostics[1].location.line, 3u);
    EXPECT_EQ(result.diagnostics[2].location.line, 5u);
    EXPECT_EQ(result.diagnostics[3].message, "unexpected '}'");
}

TEST(Loader, ColourRendering) {
    std::string text = loadProjectFromString("x = 1\n", "c.sylva").render(true);
    EXPECT_NE(text.find("\x1b[1;31merror"), std::string::npos);
}

TEST(Loader, DependencyCycle) {
    // The built-in kinds cannot form a well-typed cycle, so use a small registry.
    SchemaRegistry registry;
    AttributeSchema input;
    input.name = "input";
    input.type = ValueType::Reference;
    input.port = PortType::Elevation;
    input.target = "source";
    registry.add({"source", "smooth", PortType::Elevation, "", {input}});
    registry.add({"project", "", PortType::None, "", {}});
    registry.add({"render", "", PortType::None, "", {}});
    LoadOptions options;
    options.schema = &registry;
    const char* text =
        "source relief : smooth { input = @detail }\n"
        "source detail : smooth {\n"
        "    input = @relief\n"
        "}\n"
        "source self : smooth { input = @self }\n";
    LoadResult result = loadProjectFromString(text, "olinda.sylva", options);
    EXPECT_EQ(result.render(),
              R"(error[E0301]: dependency cycle between sources
 --> olinda.sylva:1:34
  |
1 | source relief : smooth { input = @detail }
  |                                  ^^^^^^^ 'relief' uses 'detail' here
note: 'detail' uses 'relief' at olinda.sylva:3:13
  = cycle: relief -> detail -> relief

error[E0301]: dependency cycle between sources
 --> olinda.sylva:5:32
  |
5 | source self : smooth { input = @self }
  |                                ^^^^^ 'self' uses 'self' here
  = cycle: self -> self
)");
}

TEST(Loader, GutterWidthFollowsLineNumber) {
    std::string text(9, '\n');
    text += "project { titel = \"x\" }\n";
    std::string rendered = loadProjectFromString(text, "w.sylva").render();
    EXPECT_EQ(rendered.substr(0, rendered.find("= help")),
              "error[E0208]: unknown attribute 'titel'\n"
              "  --> w.sylva:10:11\n"
              "   |\n"
              "10 | project { titel = \"x\" }\n"
              "   |           ^^^^^ not an attribute of project\n"
              "   ");
}

}  // namespace
}  // namespace sylva::dsl
