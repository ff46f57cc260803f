// ScenarioGraphs: the models of a project's scenarios and their source graphs. One
// ProjectModel per scenario (the DSL applies each scenario's overrides), one SourceGraph
// per scenario, built on first use; sources with equal content hashes share their tiles
// in a Scheduler or TileEvaluator, so a scenario recomputes only what it overrides.
//
// The first model is the default scenario (what an empty scenario name means); a project
// without scenarios has exactly one model, whose `scenario` is empty. A name that is not
// one of the models' scenarios is an error, never silently the default.
//
// Ownership: the graphs live as long as this object and do not move when it moves
// (sources are referenced by pointer from TerrainLayers and Scheduler tasks), so cancel
// or retain a Scheduler's tasks before dropping it (Scheduler::retainOnly).
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <string_view>
#include <unordered_set>
#include <vector>

#include "sylva/core/base/Result.h"
#include "sylva/core/model/ProjectModel.h"
#include "sylva/core/sources/graph/SourceGraph.h"

namespace sylva {

struct ScenarioGraph {
    const ProjectModel* model = nullptr;
    SourceGraph* graph = nullptr;
};

class ScenarioGraphs {
public:
    // Takes the models (at least one; SYLVA_CHECK) and builds the default scenario's graph
    // at once; its error (located at the offending attribute) is the error of build().
    static Result<ScenarioGraphs> build(std::vector<ProjectModel> models);

    ScenarioGraphs(ScenarioGraphs&&) noexcept;
    ScenarioGraphs& operator=(ScenarioGraphs&&) noexcept;
    ~ScenarioGraphs();

    // The first scenario's model: blocks shared by every scenario (cameras, views,
    // render, compare/blend) are read from it.
    const ProjectModel& defaultModel() const { return models_.front(); }
    const std::vector<ProjectModel>& models() const { return models_; }

    // The model and graph of `scenario` (the default scenario when empty), building the
    // graph on first use. Fails on a name that is no scenario of the project ("FILE:
    // unknown scenario 'x' (scenarios: a, b)") or when the graph cannot be built.
    Result<ScenarioGraph> scenario(std::string_view scenario);
    // The terrain layers of `scenario` (SourceGraph::terrainLayers of its graph).
    Result<TerrainLayers> terrainLayers(std::string_view scenario);
    // Builds every scenario's graph; the first error, if any (the others are still built).
    Status buildAll();

    // Over the graphs built so far: every content hash (Scheduler::retainOnly after a
    // reload) and every file their sources read (FileWatch).
    std::unordered_set<std::uint64_t> contentHashes() const;
    std::vector<std::filesystem::path> files() const;

private:
    ScenarioGraphs() = default;
    const ProjectModel* modelOf(std::string_view scenario) const;

    std::vector<ProjectModel> models_;
    // By scenario name ("" for a project without scenarios); unique_ptr keeps each
    // graph's address when the map or this object moves.
    std::map<std::string, std::unique_ptr<SourceGraph>, std::less<>> graphs_;
};

}  // namespace sylva
