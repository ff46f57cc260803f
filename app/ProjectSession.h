// ProjectSession: loads a project for a command: parses and checks it (printing every
// diagnostic to stderr), then builds the source graph. Shared by `check` and `render`.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "CommandLine.h"
#include "sylva/core/model/ProjectModel.h"
#include "sylva/core/sources/graph/SourceGraph.h"
#include "sylva/dsl/ProjectLoader.h"

namespace sylva::app {

struct ProjectSession {
    ProjectModel model;                   // the first (default) scenario's model
    std::optional<SourceGraph> graph;     // its source graph
    std::vector<ProjectModel> scenarios;  // one model per scenario (overrides applied)

    // The model and source graph of `scenario` (the default ones when empty or when the
    // project has no scenarios); graphs are built on first use. Sources with equal
    // content hashes share tiles in the TileEvaluator, so only overridden branches
    // are computed again.
    Result<std::pair<const ProjectModel*, SourceGraph*>> forScenario(const std::string& scenario);

    // nullopt after printing the reasons when the project has errors.
    std::map<std::string, SourceGraph> scenarioGraphs;

    static std::optional<ProjectSession> open(
        const std::filesystem::path& file,
        const std::vector<std::pair<std::string, std::string>>& defines);
};

// Load options from a command's -D defines, --set pairs and --lenient flag.
dsl::LoadOptions loadOptionsFor(const ParsedCommandLine& command,
                                std::vector<std::pair<std::string, std::string>> sets = {});
// Prints a load's diagnostics to stderr (colour only on a terminal).
void printDiagnostics(const dsl::LoadResult& loaded);

// Prints "sylva: <message>" to stderr.
void reportError(const std::string& message);

}  // namespace sylva::app
