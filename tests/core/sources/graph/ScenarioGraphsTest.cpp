#include "sylva/core/sources/graph/ScenarioGraphs.h"

#include <gtest/gtest.h>

#include <memory>

namespace sylva {
namespace {

const auto kFile = std::make_shared<const std::string>("hand.sylva");

Block noise(std::string name) {
    Block block;
    block.keyword = "source";
    block.name = std::move(name);
    block.kind = "noise";
    block.location = {kFile, 1, 8, 1};
    return block;
}

// One model per scenario, as the DSL makes them: the same sources, scenario `b` with
// one more (standing in for an override).
std::vector<ProjectModel> twoScenarios() {
    ProjectModel a;
    a.file = "hand.sylva";
    a.scenario = "a";
    a.sources.push_back(noise("height"));
    ProjectModel b = a;
    b.scenario = "b";
    Block other = noise("other");
    Value seed;
    seed.data = Quantity{9.0};
    other.attributes.push_back({"seed", seed, other.location});
    b.sources.push_back(other);
    return {a, b};
}

TEST(ScenarioGraphs, EachScenarioHasItsOwnModelAndGraph) {
    Result<ScenarioGraphs> graphs = ScenarioGraphs::build(twoScenarios());
    ASSERT_TRUE(graphs) << graphs.error().message;
    Result<ScenarioGraph> a = graphs->scenario("a");
    Result<ScenarioGraph> b = graphs->scenario("b");
    Result<ScenarioGraph> byDefault = graphs->scenario("");
    ASSERT_TRUE(a && b && byDefault);
    EXPECT_EQ(a->model->scenario, "a");
    EXPECT_EQ(b->model->scenario, "b");
    EXPECT_EQ(byDefault->graph, a->graph);  // empty = the first scenario
    EXPECT_NE(a->graph, b->graph);
    EXPECT_EQ(a->graph->size(), 1u);
    EXPECT_EQ(b->graph->size(), 2u);
    EXPECT_EQ(&graphs->defaultModel(), a->model);
}

TEST(ScenarioGraphs, AnUnknownScenarioIsAnErrorNotTheDefault) {
    Result<ScenarioGraphs> graphs = ScenarioGraphs::build(twoScenarios());
    ASSERT_TRUE(graphs);
    Result<ScenarioGraph> missing = graphs->scenario("c");
    ASSERT_FALSE(missing);
    EXPECT_EQ(missing.error().message, "hand.sylva: unknown scenario 'c' (scenarios: a, b)");
    EXPECT_FALSE(graphs->terrainLayers("c"));

    ProjectModel single = twoScenarios().front();
    single.scenario.clear();
    Result<ScenarioGraphs> withoutScenarios = ScenarioGraphs::build({single});
    ASSERT_TRUE(withoutScenarios);
    EXPECT_TRUE(withoutScenarios->scenario(""));
    Result<ScenarioGraph> named = withoutScenarios->scenario("a");
    ASSERT_FALSE(named);
    EXPECT_EQ(named.error().message,
              "hand.sylva: unknown scenario 'a' (the project has no scenarios)");
}

TEST(ScenarioGraphs, GraphsKeepTheirAddressWhenMovedAndCoverAllBuiltSources) {
    Result<ScenarioGraphs> built = ScenarioGraphs::build(twoScenarios());
    ASSERT_TRUE(built);
    ScenarioGraphs graphs = std::move(built.value());
    SourceGraph* first = graphs.scenario("a")->graph;
    EXPECT_EQ(graphs.contentHashes().size(), 1u);  // only the default graph is built yet
    ASSERT_TRUE(graphs.buildAll());
    ScenarioGraphs moved = std::move(graphs);
    EXPECT_EQ(moved.scenario("a")->graph, first);
    // "height" is shared (same hash), "other" only in b.
    EXPECT_EQ(moved.contentHashes().size(), 2u);
}

TEST(ScenarioGraphs, TheDefaultGraphsErrorIsTheBuildError) {
    std::vector<ProjectModel> models = twoScenarios();
    models.front().sources.front().kind = "normal_mapp";
    Result<ScenarioGraphs> graphs = ScenarioGraphs::build(models);
    ASSERT_FALSE(graphs);
    EXPECT_NE(graphs.error().message.find("hand.sylva:1:8"), std::string::npos)
        << graphs.error().message;
}

}  // namespace
}  // namespace sylva
