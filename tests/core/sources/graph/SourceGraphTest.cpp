#include "sylva/core/sources/graph/SourceGraph.h"

#include <gtest/gtest.h>

#include <memory>

namespace sylva {
namespace {

const auto kFile = std::make_shared<const std::string>("hand.sylva");

SourceLocation at(std::uint32_t line, std::uint32_t column) {
    return {kFile, line, column, 1};
}

Value reference(std::string name, SourceLocation location) {
    Value v;
    v.data = Reference{"source", std::move(name)};
    v.location = location;
    return v;
}

Block source(std::string name, std::string kind, std::uint32_t line) {
    Block block;
    block.keyword = "source";
    block.name = std::move(name);
    block.kind = std::move(kind);
    block.location = at(line, 8);
    return block;
}

void addReference(Block& block, std::string attribute, std::string target, std::uint32_t line) {
    block.attributes.push_back(
        {std::move(attribute), reference(std::move(target), at(line, 5)), at(line, 5)});
}

ProjectModel demoModel() {
    ProjectModel model;
    model.file = "hand.sylva";
    model.sources.push_back(source("height", "noise", 1));
    Block normals = source("normals", "normal_map", 2);
    addReference(normals, "height", "height", 3);
    model.sources.push_back(normals);
    Block colour = source("colour", "hypsometric", 4);
    addReference(colour, "height", "height", 5);
    addReference(colour, "normals", "normals", 6);
    model.sources.push_back(colour);
    return model;
}

TEST(SourceGraph, BuildsFromAHandMadeModel) {
    const ProjectModel model = demoModel();
    Result<SourceGraph> graph = SourceGraph::build(model);
    ASSERT_TRUE(graph) << graph.error().message;
    EXPECT_EQ(graph->size(), 3u);
    const Source* height = graph->find("height");
    const Source* normals = graph->find("normals");
    const Source* colour = graph->find("colour");
    ASSERT_TRUE(height && normals && colour);
    EXPECT_EQ(height->output(), PortType::Elevation);
    EXPECT_EQ(normals->output(), PortType::Normals);
    EXPECT_EQ(colour->output(), PortType::Image);
    ASSERT_EQ(colour->inputs().size(), 2u);
    EXPECT_EQ(colour->inputs()[0], height);
    EXPECT_EQ(colour->inputs()[1], normals);
    EXPECT_EQ(graph->find("nope"), nullptr);
}

// Issue 16: terrain whose layers carry no normals is shaded from normals derived from its
// height (a normal_map of the elevation layer, checked against an analytic slope in
// NormalMapSourceTest), not left flat.
TEST(SourceGraph, LayersWithoutNormalsGetNormalsDerivedFromTheHeight) {
    ProjectModel model = demoModel();
    Block scenario;
    scenario.keyword = "scenario";
    scenario.name = "bare";
    scenario.location = at(7, 10);
    Value layers;
    layers.data = ValueList{reference("height", at(7, 20)), reference("colour", at(7, 29))};
    layers.location = at(7, 19);
    scenario.attributes.push_back({"layers", layers, at(7, 12)});
    model.scenarios.push_back(scenario);
    Result<SourceGraph> graph = SourceGraph::build(model);
    ASSERT_TRUE(graph) << graph.error().message;
    Result<TerrainLayers> terrain = graph->terrainLayers(model, "bare");
    ASSERT_TRUE(terrain) << terrain.error().message;
    ASSERT_NE(terrain->normals, nullptr);
    EXPECT_EQ(terrain->normals->output(), PortType::Normals);
    EXPECT_EQ(terrain->normals->name(), "height.normals");
    ASSERT_EQ(terrain->normals->inputs().size(), 1u);
    EXPECT_EQ(terrain->normals->inputs()[0], graph->find("height"));
}

TEST(SourceGraph, InputsDefinedLaterAreBuiltFirst) {
    ProjectModel model = demoModel();
    std::swap(model.sources.front(), model.sources.back());
    Result<SourceGraph> graph = SourceGraph::build(model);
    ASSERT_TRUE(graph) << graph.error().message;
    EXPECT_EQ(graph->size(), 3u);
}

TEST(SourceGraph, UnknownKindIsLocated) {
    ProjectModel model = demoModel();
    model.sources.push_back(source("odd", "normal_mapp", 9));
    Result<SourceGraph> graph = SourceGraph::build(model);
    ASSERT_FALSE(graph);
    EXPECT_EQ(graph.error().message,
              "hand.sylva:9:8: source 'odd': unknown source kind 'normal_mapp'");
}

TEST(SourceGraph, MissingInputIsLocated) {
    ProjectModel model;
    model.file = "hand.sylva";
    model.sources.push_back(source("normals", "normal_map", 4));
    Result<SourceGraph> graph = SourceGraph::build(model);
    ASSERT_FALSE(graph);
    EXPECT_NE(graph.error().message.find("hand.sylva:4:8"), std::string::npos)
        << graph.error().message;
    EXPECT_NE(graph.error().message.find("'normals'"), std::string::npos) << graph.error().message;
    EXPECT_NE(graph.error().message.find("missing input 'height'"), std::string::npos)
        << graph.error().message;
}

TEST(SourceGraph, UnknownInputIsLocated) {
    ProjectModel model;
    model.file = "hand.sylva";
    Block normals = source("normals", "normal_map", 4);
    addReference(normals, "height", "heigth", 5);
    model.sources.push_back(normals);
    Result<SourceGraph> graph = SourceGraph::build(model);
    ASSERT_FALSE(graph);
    EXPECT_EQ(graph.error().message, "hand.sylva:5:5: source 'normals': unknown source 'heigth'");
}

TEST(SourceGraph, WrongPortTypeIsLocated) {
    ProjectModel model = demoModel();
    Block shade = source("shade", "normal_map", 10);
    addReference(shade, "height", "colour", 11);
    model.sources.push_back(shade);
    Result<SourceGraph> graph = SourceGraph::build(model);
    ASSERT_FALSE(graph);
    EXPECT_EQ(graph.error().message,
              "hand.sylva:11:5: source 'shade': 'height' expects elevation, but source 'colour' "
              "gives image");
}

TEST(SourceGraph, CycleIsLocated) {
    ProjectModel model;
    model.file = "hand.sylva";
    Block a = source("a", "hypsometric", 1);
    addReference(a, "height", "b", 2);
    Block b = source("b", "normal_map", 3);
    addReference(b, "height", "a", 4);
    model.sources.push_back(a);
    model.sources.push_back(b);
    Result<SourceGraph> graph = SourceGraph::build(model);
    ASSERT_FALSE(graph);
    EXPECT_NE(graph.error().message.find("dependency cycle through source 'a'"), std::string::npos)
        << graph.error().message;
}

}  // namespace
}  // namespace sylva
