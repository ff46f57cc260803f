// `sylva check PROJECT [-D name=value] [--set block.attr=value] [--print-params]
// [--lenient] [--diagnostics=text|json]`: every diagnostic of the project, no rendering.
// Exit code 0 clean (warnings allowed), 1 errors in the project or its data, 2 usage.
#include <cstdio>

#include <nlohmann/json.hpp>

#include "CommandLine.h"
#include "Commands.h"
#include "ProjectSession.h"
#include "sylva/core/sources/graph/SourceGraph.h"
#include "sylva/dsl/ModelHash.h"
#include "sylva/dsl/ProjectLoader.h"
#include "sylva/dsl/Resolver.h"

namespace sylva::app {

namespace {

nlohmann::ordered_json locationJson(const SourceLocation& location) {
    nlohmann::ordered_json out;
    if (location.valid()) {
        out["file"] = *location.file;
        out["line"] = location.line;
        out["column"] = location.column;
        out["length"] = location.length;
    }
    return out;
}

std::string diagnosticsJson(const dsl::LoadResult& result) {
    nlohmann::ordered_json list = nlohmann::ordered_json::array();
    for (const dsl::Diagnostic& diagnostic : result.diagnostics) {
        nlohmann::ordered_json item;
        item["severity"] = diagnostic.severity == dsl::Severity::Error     ? "error"
                           : diagnostic.severity == dsl::Severity::Warning ? "warning"
                                                                           : "note";
        item["code"] = diagnostic.code;
        item["message"] = diagnostic.message;
        item["location"] = locationJson(diagnostic.location);
        item["label"] = diagnostic.label;
        nlohmann::ordered_json notes = nlohmann::ordered_json::array();
        for (const dsl::DiagnosticNote& note : diagnostic.notes) {
            notes.push_back({{"message", note.message}, {"location", locationJson(note.location)}});
        }
        item["notes"] = notes;
        item["help"] = diagnostic.help;
        if (!diagnostic.cycle.empty()) {
            item["cycle"] = diagnostic.cycle;
        }
        list.push_back(item);
    }
    nlohmann::ordered_json root;
    root["errors"] = result.hasErrors();
    root["diagnostics"] = list;
    return root.dump(2) + "\n";
}

std::string valueText(const Value& value) {
    if (const Quantity* quantity = value.get<Quantity>()) {
        return dsl::formatQuantity(*quantity);
    }
    if (const std::string* text = value.get<std::string>()) {
        return "\"" + *text + "\"";
    }
    if (const bool* flag = value.get<bool>()) {
        return *flag ? "true" : "false";
    }
    return dsl::canonicalText(value);
}

}  // namespace

std::vector<std::pair<std::string, std::string>> extractSets(std::vector<std::string>& arguments,
                                                             std::string& error) {
    std::vector<std::pair<std::string, std::string>> sets;
    std::vector<std::string> rest;
    for (std::size_t i = 0; i < arguments.size(); ++i) {
        std::string assignment;
        if (arguments[i] == "--set") {
            if (i + 1 >= arguments.size()) {
                error = "--set needs block.attribute=value";
                return sets;
            }
            assignment = arguments[++i];
        } else if (arguments[i].rfind("--set=", 0) == 0) {
            assignment = arguments[i].substr(6);
        } else {
            rest.push_back(arguments[i]);
            continue;
        }
        std::size_t equals = assignment.find('=');
        if (equals == std::string::npos || equals == 0) {
            error = "--set needs block.attribute=value, got '" + assignment + "'";
            return sets;
        }
        sets.emplace_back(assignment.substr(0, equals), assignment.substr(equals + 1));
    }
    arguments = std::move(rest);
    return sets;
}

int runCheck(const std::vector<std::string>& originalArguments) {
    std::vector<std::string> arguments = originalArguments;
    std::string setError;
    auto sets = extractSets(arguments, setError);
    const ParsedCommandLine command = parseCommandLine(
        arguments,
        {{"help", false}, {"print-params", false}, {"lenient", false}, {"diagnostics", true}});
    if (command.has("help")) {
        std::puts(
            "usage: sylva check PROJECT [-D name=value] [--set block.attr=value] [--print-params]\n"
            "                   [--lenient] [--diagnostics=text|json]\n"
            "exit code: 0 no errors, 1 errors, 2 usage error");
        return 0;
    }
    std::string format = command.get("diagnostics").value_or("text");
    std::string error = !setError.empty() ? setError : command.error;
    if (error.empty() && command.positional.size() != 1) {
        error = "check needs exactly one project file";
    }
    if (error.empty() && format != "text" && format != "json") {
        error = "--diagnostics must be text or json, got '" + format + "'";
    }
    if (!error.empty()) {
        reportError(error);
        return 2;
    }
    dsl::LoadResult loaded = dsl::loadProject(command.positional[0], loadOptionsFor(command, sets));
    if (format == "json") {
        std::fputs(diagnosticsJson(loaded).c_str(), stdout);
    } else {
        printDiagnostics(loaded);
    }
    if (loaded.hasErrors() || !loaded.model) {
        return 1;
    }
    std::vector<const ProjectModel*> models;
    if (loaded.scenarios.empty()) {
        models.push_back(&*loaded.model);
    }
    for (const ProjectModel& scenario : loaded.scenarios) {
        models.push_back(&scenario);
    }
    // The data behind the project (files, bands, ports) is checked by building the graph.
    for (const ProjectModel* model : models) {
        Result<SourceGraph> graph = SourceGraph::build(*model);
        if (!graph) {
            reportError(graph.error().message);
            return 1;
        }
    }
    const ProjectModel& model = *loaded.model;
    if (command.has("print-params")) {
        for (const Block& param : model.params) {
            const Attribute* value = param.find("value");
            if (!value) {
                continue;
            }
            bool fromCommandLine =
                value->value.location.file && *value->value.location.file == "<command line>";
            std::printf(
                "%s = %s    (%s)\n", param.name.c_str(), valueText(value->value).c_str(),
                fromCommandLine ? "from -D" : ("default at " + param.location.toString()).c_str());
        }
    }
    if (format == "text") {
        std::printf("%s: ok (%zu sources, %zu cameras, %zu views)\n", command.positional[0].c_str(),
                    model.sources.size(), model.cameras.size(), model.views.size());
    }
    return 0;
}

}  // namespace sylva::app
