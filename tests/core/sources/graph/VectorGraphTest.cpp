// The vector kinds built through SourceGraph from a hand-made model: typed inputs are
// checked by the graph, with located messages.
#include <gtest/gtest.h>

#include <memory>

#include "sylva/core/sources/graph/SourceGraph.h"
#include "sylva/core/sources/plants/PlantsSource.h"

namespace sylva {
namespace {

const auto kFile = std::make_shared<const std::string>("vector.sylva");

Block source(std::string name, std::string kind, std::uint32_t line) {
    Block block;
    block.keyword = "source";
    block.name = std::move(name);
    block.kind = std::move(kind);
    block.location = {kFile, line, 8, 1};
    return block;
}

void set(Block& block, std::string attribute, Value value, std::uint32_t line) {
    value.location = {kFile, line, 5, 1};
    block.attributes.push_back({std::move(attribute), value, value.location});
}

Value reference(std::string name) {
    Value v;
    v.data = Reference{"source", std::move(name)};
    return v;
}

Value text(std::string s) {
    Value v;
    v.data = std::move(s);
    return v;
}

ProjectModel model(bool elevationFromFeatures, bool bothInputs) {
    ProjectModel m;
    m.file = "vector.sylva";
    m.sources.push_back(source("hills", "noise", 1));
    Block world = source("world", "features", 2);
    set(world, "file", text("world.gpkg"), 2);
    m.sources.push_back(world);
    Block trees = source("trees", "plants", 3);
    set(trees, "elevation", reference(elevationFromFeatures ? "world" : "hills"), 4);
    set(trees, "features", reference("world"), 5);
    Value species;
    species.data = ValueObject{{"oak", Value{Quantity{1.0, Dimension::Ratio}, {}}}};
    set(trees, "species", species, 6);
    m.sources.push_back(trees);
    Block markers = source("markers", "rasterize", 7);
    set(markers, "instances", reference("trees"), 8);
    if (bothInputs) {
        set(markers, "features", reference("world"), 9);
    }
    m.sources.push_back(markers);
    return m;
}

TEST(VectorGraph, BuildsAndChecksInputs) {
    Result<SourceGraph> graph = SourceGraph::build(model(false, false));
    ASSERT_TRUE(graph) << graph.error().message;
    EXPECT_EQ(graph->find("world")->output(), PortType::Features);
    EXPECT_EQ(graph->find("trees")->output(), PortType::Instances);
    EXPECT_EQ(graph->find("markers")->output(), PortType::Image);
    EXPECT_NE(PlantsSource::from(graph->find("trees")), nullptr);

    Result<SourceGraph> wrong = SourceGraph::build(model(true, false));
    ASSERT_FALSE(wrong);
    EXPECT_EQ(wrong.error().message,
              "vector.sylva:4:5: source 'trees': 'elevation' expects elevation, but source 'world' "
              "gives features");

    Result<SourceGraph> both = SourceGraph::build(model(false, true));
    ASSERT_FALSE(both);
    EXPECT_EQ(both.error().message,
              "vector.sylva:7:8: source 'markers': rasterize takes exactly one of 'features' and "
              "'instances'");
}

}  // namespace
}  // namespace sylva
