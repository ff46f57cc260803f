// `sylva bench SUITE [--json]`: benchmark suites, dispatched from one table so other
// suites can be added as one line each. Suite `dsl` parses, resolves and checks a
// generated project of 5,000 lines (500 sources, 20 scenarios, 50 cameras). Suite
// `vector` measures rasterize (polygons with outlines) and plants (scattering) tiles;
// `plants` the plant generator, importer and billboard-cloud builder; `analysis` the
// bare-earth ZTV against GDAL's viewshed. Their bodies are
// in sylva_bench (bench/DslBenchmark.h, VectorBenchmark.h, PlantsBenchmark.h); the
// suites with options of their own have their own commands (runTerrainBench, ...).
#include <cstdio>
#include <functional>
#include <initializer_list>
#include <string>
#include <string_view>

#include "CommandLine.h"
#include "Commands.h"
#include "ProjectSession.h"
#include "sylva/bench/AnalysisBenchmark.h"
#include "sylva/bench/DslBenchmark.h"
#include "sylva/bench/PlantsBenchmark.h"
#include "sylva/bench/VectorBenchmark.h"

namespace sylva::app {

namespace {

// Appends every piece to `out` (one call per line keeps GCC's -Wrestrict quiet, which
// misfires on chains of temporary strings).
void append(std::string& out, std::initializer_list<std::string_view> pieces) {
    for (std::string_view piece : pieces) {
        out.append(piece);
    }
}

// Prints a suite's metrics: its JSON with --json, else one "SUITE.KEY = VALUE" line each.
template <typename SuiteResult>
int printMetrics(const char* suite, const Result<SuiteResult>& result, bool json) {
    if (!result) {
        reportError(result.error().message);
        return 1;
    }
    if (json) {
        std::puts(result->json().c_str());
        return 0;
    }
    for (const auto& [name, value] : result->metrics) {
        std::printf("%s.%s = %.3f\n", suite, name.c_str(), value);
    }
    return 0;
}

struct Suite {
    const char* name;
    std::function<int(bool json)> run;
};

// One line per suite.
const Suite kSuites[] = {
    {"dsl", [](bool json) { return printMetrics("dsl", bench::runDslBenchmark({}), json); }},
    {"vector",
     [](bool json) { return printMetrics("vector", bench::runVectorBenchmark({}), json); }},
    {"plants",
     [](bool json) { return printMetrics("plants", bench::runPlantsBenchmark({}), json); }},
    {"analysis",
     [](bool json) { return printMetrics("analysis", bench::runAnalysisBenchmark({}), json); }},
};

}  // namespace

int runBench(const std::vector<std::string>& arguments) {
    // Suites with options and structured output of their own take over the command.
    if (!arguments.empty() && arguments[0] == "terrain") {
        return runTerrainBench(std::vector<std::string>(arguments.begin() + 1, arguments.end()));
    }
    if (!arguments.empty() && arguments[0] == "tiles") {
        return runTilesBench(std::vector<std::string>(arguments.begin() + 1, arguments.end()));
    }
    if (!arguments.empty() && arguments[0] == "vegetation") {
        return runVegetationBench(std::vector<std::string>(arguments.begin() + 1, arguments.end()));
    }
    if (!arguments.empty() && arguments[0] == "turnaround") {
        return runTurnaroundBench(std::vector<std::string>(arguments.begin() + 1, arguments.end()));
    }
    if (!arguments.empty() && arguments[0] == "plantlod") {
        return runPlantLodBench(std::vector<std::string>(arguments.begin() + 1, arguments.end()));
    }
    const ParsedCommandLine command =
        parseCommandLine(arguments, {{"help", false}, {"json", false}});
    std::string names;
    for (const Suite& suite : kSuites) {
        append(names, {names.empty() ? "" : ", ", suite.name});
    }
    if (command.has("help")) {
        std::printf(
            "usage: sylva bench SUITE [--json]\nsuites: %s, terrain, tiles, plantlod, turnaround, "
            "vegetation\n",
            names.c_str());
        return 0;
    }
    if (!command.error.empty() || command.positional.size() != 1) {
        reportError(command.error.empty() ? "bench needs one suite: " + names +
                                                ", terrain, tiles, plantlod, turnaround, vegetation"
                                          : command.error);
        return 2;
    }
    for (const Suite& suite : kSuites) {
        if (command.positional[0] == suite.name) {
            return suite.run(command.has("json"));
        }
    }
    reportError("unknown bench suite '" + command.positional[0] + "' (suites: " + names + ")");
    return 2;
}

}  // namespace sylva::app
