// `sylva doc [KIND] [--markdown] [--update FILE]`: the language reference from the
// schema registry. --update rewrites the generated part of FILE (docs/dsl.md).
#include <cstdio>
#include <fstream>
#include <iterator>

#include "CommandLine.h"
#include "Commands.h"
#include "ProjectSession.h"
#include "sylva/dsl/EditDistance.h"
#include "sylva/dsl/SchemaReference.h"

namespace sylva::app {

int runDoc(const std::vector<std::string>& arguments) {
    const ParsedCommandLine command =
        parseCommandLine(arguments, {{"help", false}, {"markdown", false}, {"update", true}});
    if (command.has("help")) {
        std::puts("usage: sylva doc [KIND] [--markdown] [--update FILE]");
        return 0;
    }
    if (!command.error.empty() || command.positional.size() > 1) {
        reportError(command.error.empty() ? "doc takes at most one kind" : command.error);
        return 2;
    }
    const SchemaRegistry& registry = SchemaRegistry::builtin();
    if (auto file = command.get("update")) {
        std::ifstream in(*file, std::ios::binary);
        std::string document((std::istreambuf_iterator<char>(in)),
                             std::istreambuf_iterator<char>());
        std::string updated = dsl::SchemaReference::replaceGenerated(document, registry);
        if (updated.empty()) {
            reportError("'" + *file + "' has no generated-reference markers");
            return 1;
        }
        if (updated != document) {
            std::ofstream out(*file, std::ios::binary | std::ios::trunc);
            out << updated;
        }
        return 0;
    }
    if (command.has("markdown")) {
        std::fputs(dsl::SchemaReference::markdown(registry).c_str(), stdout);
        return 0;
    }
    if (command.positional.empty()) {
        std::puts("Blocks and source kinds (sylva doc KIND for details):");
        for (const KindSchema& kind : registry.all()) {
            std::printf("  %-14s %s\n",
                        (kind.keyword == "source" ? kind.kind : kind.keyword).c_str(),
                        kind.keyword == "source" ? "source kind" : "block");
        }
        return 0;
    }
    std::string text = dsl::SchemaReference::text(registry, command.positional[0]);
    if (text.empty()) {
        std::string message = "no block or source kind named '" + command.positional[0] + "'";
        if (auto match =
                dsl::closestMatch(command.positional[0], dsl::SchemaReference::names(registry))) {
            message += "; did you mean '" + *match + "'?";
        }
        reportError(message);
        return 1;
    }
    std::fputs(text.c_str(), stdout);
    return 0;
}

}  // namespace sylva::app
