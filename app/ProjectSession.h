// ProjectSession: loads a project for a command: parses and checks it (printing every
// diagnostic to stderr), then builds the default scenario's source graph (the others on
// first use). Used by `bench turnaround`; `render` and `watch` hand the models to
// render::BatchRenderer instead.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "CommandLine.h"
#include "sylva/core/model/ProjectModel.h"
#include "sylva/core/sources/graph/ScenarioGraphs.h"
#include "sylva/core/sources/graph/SourceGraph.h"
#include "sylva/dsl/ProjectLoader.h"

namespace sylva::app {

struct ProjectSession {
    ProjectModel model;                    // the first (default) scenario's model
    SourceGraph* graph = nullptr;          // its source graph (owned by `graphs`)
    std::optional<ScenarioGraphs> graphs;  // every scenario's model and graph

    // The model and source graph of `scenario` (the default ones when empty); graphs
    // are built on first use. Sources with equal content hashes share tiles in the
    // TileEvaluator, so only overridden branches are computed again. A name that is no
    // scenario of the project is an error (ScenarioGraphs::scenario).
    Result<std::pair<const ProjectModel*, SourceGraph*>> forScenario(const std::string& scenario);

    // nullopt after printing the reasons when the project has errors.
    static std::optional<ProjectSession> open(
        const std::filesystem::path& file,
        const std::vector<std::pair<std::string, std::string>>& defines);
};

// The models of a load without errors, one per scenario in the project's order (the
// project's one model when it has no scenarios): what ScenarioGraphs and
// render::BatchRenderer take.
std::vector<ProjectModel> scenarioModels(dsl::LoadResult&& loaded);

// Load options from a command's -D defines, --set pairs and --lenient flag.
dsl::LoadOptions loadOptionsFor(const ParsedCommandLine& command,
                                std::vector<std::pair<std::string, std::string>> sets = {});
// Prints a load's diagnostics to stderr (colour only on a terminal).
void printDiagnostics(const dsl::LoadResult& loaded);

// Prints "sylva: <message>" to stderr.
void reportError(const std::string& message);

}  // namespace sylva::app
