// `sylva dump --json PROJECT [-D name=value] [--set block.attr=value] [--lenient]`: the
// evaluated model of every scenario as JSON on stdout (diagnostics on stderr).
#include <cstdio>

#include "CommandLine.h"
#include "Commands.h"
#include "ProjectSession.h"
#include "sylva/dsl/ModelJson.h"
#include "sylva/dsl/ProjectLoader.h"

namespace sylva::app {

int runDump(const std::vector<std::string>& originalArguments) {
    std::vector<std::string> arguments = originalArguments;
    std::string setError;
    auto sets = extractSets(arguments, setError);
    const ParsedCommandLine command =
        parseCommandLine(arguments, {{"help", false}, {"json", false}, {"lenient", false}});
    if (command.has("help")) {
        std::puts("usage: sylva dump --json PROJECT [-D name=value] [--set block.attr=value]");
        return 0;
    }
    std::string error = !setError.empty() ? setError : command.error;
    if (error.empty() && command.positional.size() != 1) {
        error = "dump needs exactly one project file";
    }
    if (error.empty() && !command.has("json")) {
        error = "dump needs --json (the only output format)";
    }
    if (!error.empty()) {
        reportError(error);
        return 2;
    }
    dsl::LoadResult loaded = dsl::loadProject(command.positional[0], loadOptionsFor(command, sets));
    printDiagnostics(loaded);
    if (loaded.hasErrors() || !loaded.model) {
        return 1;
    }
    std::vector<ProjectModel> models = loaded.scenarios;
    if (models.empty()) {
        models.push_back(*loaded.model);
    }
    std::fputs(dsl::modelsToJson(models).c_str(), stdout);
    return 0;
}

}  // namespace sylva::app
