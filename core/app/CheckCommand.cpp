// `sylva check PROJECT [-D name=value]`: every diagnostic of the project, no rendering.
#include <cstdio>

#include "CommandLine.h"
#include "Commands.h"
#include "ProjectSession.h"

namespace sylva::app {

int runCheck(const std::vector<std::string>& arguments) {
    const ParsedCommandLine command = parseCommandLine(arguments, {{"help", false}});
    if (command.has("help")) {
        std::puts("usage: sylva check PROJECT [-D name=value]");
        return 0;
    }
    if (!command.error.empty() || command.positional.size() != 1) {
        reportError(command.error.empty() ? "check needs exactly one project file" : command.error);
        return 2;
    }
    std::optional<ProjectSession> session = ProjectSession::open(command.positional[0], command.defines);
    if (!session) {
        return 1;
    }
    std::printf("%s: ok (%zu sources, %zu cameras, %zu views)\n", command.positional[0].c_str(),
                session->model.sources.size(), session->model.cameras.size(), session->model.views.size());
    return 0;
}

}  // namespace sylva::app
