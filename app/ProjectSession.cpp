#include "ProjectSession.h"

#include <unistd.h>

#include <cstdio>

#include "sylva/core/base/Check.h"
#include "sylva/dsl/ProjectLoader.h"

namespace sylva::app {

void reportError(const std::string& message) {
    std::fprintf(stderr, "sylva: %s\n", message.c_str());
}

dsl::LoadOptions loadOptionsFor(const ParsedCommandLine& command,
                                std::vector<std::pair<std::string, std::string>> sets) {
    dsl::LoadOptions options;
    options.defines = command.defines;
    options.sets = std::move(sets);
    options.lenient = command.has("lenient");
    return options;
}

void printDiagnostics(const dsl::LoadResult& loaded) {
    if (loaded.diagnostics.empty()) {
        return;
    }
    const std::string text = loaded.render(isatty(fileno(stderr)) != 0);
    std::fputs(text.c_str(), stderr);
    if (!text.empty() && text.back() != '\n') {
        std::fputc('\n', stderr);
    }
}

std::vector<ProjectModel> scenarioModels(dsl::LoadResult&& loaded) {
    SYLVA_CHECK(!loaded.hasErrors() && loaded.model.has_value());
    if (loaded.scenarios.empty()) {
        return {std::move(*loaded.model)};
    }
    return std::move(loaded.scenarios);
}

std::optional<ProjectSession> ProjectSession::open(
    const std::filesystem::path& file,
    const std::vector<std::pair<std::string, std::string>>& defines) {
    dsl::LoadOptions options;
    options.defines = defines;
    dsl::LoadResult loaded = dsl::loadProject(file, options);
    printDiagnostics(loaded);
    if (loaded.hasErrors() || !loaded.model) {
        return std::nullopt;
    }
    Result<ScenarioGraphs> graphs = ScenarioGraphs::build(scenarioModels(std::move(loaded)));
    if (!graphs) {
        reportError(graphs.error().message);
        return std::nullopt;
    }
    ProjectSession session;
    session.model = graphs->defaultModel();
    session.graphs.emplace(std::move(graphs.value()));
    session.graph = session.graphs->scenario("")->graph;
    return session;
}

Result<std::pair<const ProjectModel*, SourceGraph*>> ProjectSession::forScenario(
    const std::string& scenario) {
    Result<ScenarioGraph> found = graphs->scenario(scenario);
    if (!found) {
        return found.error();
    }
    return std::make_pair(found->model, found->graph);
}

}  // namespace sylva::app
