// ProjectSession: loads a project for a command: parses and checks it (printing every
// diagnostic to stderr), then builds the source graph. Shared by `check` and `render`.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "sylva/core/scene/ProjectModel.h"
#include "sylva/core/sources/SourceGraph.h"

namespace sylva::app {

struct ProjectSession {
    ProjectModel model;
    std::optional<SourceGraph> graph;

    // nullopt after printing the reasons when the project has errors.
    static std::optional<ProjectSession> open(const std::filesystem::path& file,
                                              const std::vector<std::pair<std::string, std::string>>& defines);
};

// Prints "sylva: <message>" to stderr.
void reportError(const std::string& message);

}  // namespace sylva::app
