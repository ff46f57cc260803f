#include "sylva/core/sources/graph/ScenarioGraphs.h"

#include "sylva/core/base/Check.h"

namespace sylva {

ScenarioGraphs::ScenarioGraphs(ScenarioGraphs&&) noexcept = default;
ScenarioGraphs& ScenarioGraphs::operator=(ScenarioGraphs&&) noexcept = default;
ScenarioGraphs::~ScenarioGraphs() = default;

Result<ScenarioGraphs> ScenarioGraphs::build(std::vector<ProjectModel> models) {
    SYLVA_CHECK(!models.empty());
    ScenarioGraphs graphs;
    graphs.models_ = std::move(models);
    Result<ScenarioGraph> first = graphs.scenario(graphs.defaultModel().scenario);
    if (!first) {
        return first.error();
    }
    return graphs;
}

const ProjectModel* ScenarioGraphs::modelOf(std::string_view scenario) const {
    if (scenario.empty()) {
        return &models_.front();
    }
    for (const ProjectModel& model : models_) {
        if (model.scenario == scenario) {
            return &model;
        }
    }
    return nullptr;
}

Result<ScenarioGraph> ScenarioGraphs::scenario(std::string_view scenario) {
    const ProjectModel* model = modelOf(scenario);
    if (model == nullptr) {
        std::string known;
        for (const ProjectModel& candidate : models_) {
            if (!candidate.scenario.empty()) {
                known += (known.empty() ? "" : ", ") + candidate.scenario;
            }
        }
        return Error{
            defaultModel().file.string() + ": unknown scenario '" + std::string(scenario) + "' (" +
            (known.empty() ? std::string("the project has no scenarios") : "scenarios: " + known) +
            ")"};
    }
    auto found = graphs_.find(model->scenario);
    if (found == graphs_.end()) {
        Result<SourceGraph> built = SourceGraph::build(*model);
        if (!built) {
            return built.error();
        }
        found =
            graphs_
                .emplace(model->scenario, std::make_unique<SourceGraph>(std::move(built.value())))
                .first;
    }
    return ScenarioGraph{model, found->second.get()};
}

Result<TerrainLayers> ScenarioGraphs::terrainLayers(std::string_view scenario) {
    Result<ScenarioGraph> found = this->scenario(scenario);
    if (!found) {
        return found.error();
    }
    return found->graph->terrainLayers(*found->model, scenario);
}

Status ScenarioGraphs::buildAll() {
    Status first;
    for (const ProjectModel& model : models_) {
        if (Result<ScenarioGraph> built = scenario(model.scenario); !built && first) {
            first = built.error();
        }
    }
    return first;
}

std::unordered_set<std::uint64_t> ScenarioGraphs::contentHashes() const {
    std::unordered_set<std::uint64_t> hashes;
    for (const auto& [name, graph] : graphs_) {
        const std::unordered_set<std::uint64_t> ofGraph = graph->contentHashes();
        hashes.insert(ofGraph.begin(), ofGraph.end());
    }
    return hashes;
}

std::vector<std::filesystem::path> ScenarioGraphs::files() const {
    std::vector<std::filesystem::path> files;
    for (const auto& [name, graph] : graphs_) {
        for (const std::filesystem::path& file : graph->files()) {
            files.push_back(file);
        }
    }
    return files;
}

}  // namespace sylva
