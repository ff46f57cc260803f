// `sylva fmt [--check] FILES...`: rewrites project files in canonical layout, keeping
// every comment. --check only reports files that would change (exit 1 if any).
// Files with syntax errors are left untouched and reported (exit 1).
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <iterator>

#include "CommandLine.h"
#include "Commands.h"
#include "ProjectSession.h"
#include "sylva/dsl/DiagnosticRenderer.h"
#include "sylva/dsl/Formatter.h"

namespace sylva::app {

int runFmt(const std::vector<std::string>& arguments) {
    const ParsedCommandLine command =
        parseCommandLine(arguments, {{"help", false}, {"check", false}});
    if (command.has("help")) {
        std::puts("usage: sylva fmt [--check] FILES...");
        return 0;
    }
    if (!command.error.empty() || command.positional.empty() || !command.defines.empty()) {
        reportError(command.error.empty() ? "fmt needs one or more project files" : command.error);
        return 2;
    }
    const bool check = command.has("check");
    int status = 0;
    for (const std::string& name : command.positional) {
        std::ifstream in(name, std::ios::binary);
        if (!in) {
            reportError("cannot read '" + name + "'");
            status = 1;
            continue;
        }
        std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        in.close();
        dsl::SourceFiles sources;
        std::vector<dsl::Diagnostic> diagnostics;
        std::optional<std::string> formatted =
            dsl::Formatter::format(text, name, sources, diagnostics);
        if (!formatted) {
            std::fputs(dsl::DiagnosticRenderer(sources)
                           .render(diagnostics, isatty(fileno(stderr)) != 0)
                           .c_str(),
                       stderr);
            status = 1;
            continue;
        }
        if (*formatted == text) {
            continue;
        }
        if (check) {
            std::printf("%s: not formatted\n", name.c_str());
            status = 1;
            continue;
        }
        std::ofstream out(name, std::ios::binary | std::ios::trunc);
        out << *formatted;
        if (!out) {
            reportError("cannot write '" + name + "'");
            status = 1;
        }
    }
    return status;
}

}  // namespace sylva::app
