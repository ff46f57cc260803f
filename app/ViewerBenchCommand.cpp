// `sylva bench viewer [--json] [--project FILE] [--size WxH] [--budget-ms N] [--steps N]
// [--still N] [--trace] [--disk-cache DIR]`: the interactive viewer's frame budget on a scripted
// Olinda flight (bench/ViewerBenchmark.h). Prints the metrics as JSON with --json, else one line
// each.
#include <cstdio>

#include "CommandLine.h"
#include "Commands.h"
#include "ProjectSession.h"
#include "sylva/bench/ViewerBenchmark.h"

namespace sylva::app {

int runViewerBench(const std::vector<std::string>& arguments) {
    const ParsedCommandLine command = parseCommandLine(arguments, {{"json", false},
                                                                   {"project"},
                                                                   {"size"},
                                                                   {"budget-ms"},
                                                                   {"steps"},
                                                                   {"still"},
                                                                   {"trace", false},
                                                                   {"disk-cache"}});
    if (!command.error.empty() || !command.positional.empty()) {
        reportError(command.error.empty() ? "bench viewer takes no arguments" : command.error);
        return 2;
    }
    bench::ViewerBenchmarkOptions options;
    options.project = command.get("project").value_or(options.project.string());
    if (std::optional<std::string> size = command.get("size");
        size && !parseSize(*size, options.width, options.height)) {
        reportError("--size expects WIDTHxHEIGHT within 1..16384, got '" + *size + "'");
        return 2;
    }
    int budget = static_cast<int>(options.budgetMilliseconds);
    for (auto [name, target] : {std::pair<const char*, int*>{"budget-ms", &budget},
                                {"steps", &options.flightSteps},
                                {"still", &options.stillFrames}}) {
        const Result<std::optional<int>> value =
            wholeNumberOption(command, name, 1, 100000, "expects a whole number within 1..100000");
        if (!value) {
            reportError(value.error().message);
            return 2;
        }
        *target = value.value().value_or(*target);
    }
    options.budgetMilliseconds = budget;
    if (std::optional<std::string> folder = command.get("disk-cache")) {
        options.diskCache = *folder;  // cold on the first run into it, warm after
    }
    if (command.has("trace")) {
        options.trace = stderr;  // one line per frame
    }
    Result<bench::ViewerBenchmarkResult> result = bench::runViewerBenchmark(options);
    if (!result) {
        reportError(result.error().message);
        return 1;
    }
    if (command.has("json")) {
        std::puts(result->json().c_str());
    } else {
        for (const auto& [name, value] : result->metrics) {
            std::printf("viewer.%s = %.3f\n", name.c_str(), value);
        }
    }
    return 0;
}

}  // namespace sylva::app
