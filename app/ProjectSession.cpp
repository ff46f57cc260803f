#include "ProjectSession.h"

#include <unistd.h>

#include <cstdio>

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
    ProjectSession session;
    session.model = std::move(*loaded.model);
    session.scenarios = std::move(loaded.scenarios);
    Result<SourceGraph> graph = SourceGraph::build(session.model);
    if (!graph) {
        reportError(graph.error().message);
        return std::nullopt;
    }
    session.graph.emplace(std::move(graph.value()));
    return session;
}

Result<std::pair<const ProjectModel*, SourceGraph*>> ProjectSession::forScenario(
    const std::string& scenario) {
    const ProjectModel* scenarioModel = nullptr;
    for (const ProjectModel& candidate : scenarios) {
        if (candidate.scenario == scenario) {
            scenarioModel = &candidate;
        }
    }
    if (scenario.empty() || scenarioModel == nullptr || scenarioModel == &scenarios.front()) {
        return std::make_pair(static_cast<const ProjectModel*>(&model), &*graph);
    }
    auto it = scenarioGraphs.find(scenario);
    if (it == scenarioGraphs.end()) {
        Result<SourceGraph> built = SourceGraph::build(*scenarioModel);
        if (!built) {
            return built.error();
        }
        it = scenarioGraphs.emplace(scenario, std::move(built.value())).first;
    }
    return std::make_pair(scenarioModel, &it->second);
}

}  // namespace sylva::app
