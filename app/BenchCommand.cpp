// `sylva bench SUITE [--json]`: benchmark suites, dispatched from one table so other
// suites can be added as one line each. Suite `dsl` parses, resolves and checks a
// generated project of 5,000 lines (500 sources, 20 scenarios, 50 cameras). Suite
// `vector` measures rasterize (polygons with outlines) and plants (scattering) tiles;
// `plants` the plant generator, importer and billboard-cloud builder; `analysis` the
// bare-earth ZTV against GDAL's viewshed; `views` planar and cylindrical renders and
// camera matching (bench/ViewsBenchmark.h). Their bodies are
// in sylva_bench (bench/DslBenchmark.h, VectorBenchmark.h, PlantsBenchmark.h); the
// suites with options of their own have their own commands (runTerrainBench, ...).
#include <cstdio>
#include <functional>
#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

#include "CommandLine.h"
#include "Commands.h"
#include "ProjectSession.h"
#include "sylva/bench/AnalysisBenchmark.h"
#include "sylva/bench/DslBenchmark.h"
#include "sylva/bench/PlantsBenchmark.h"
#include "sylva/bench/VectorBenchmark.h"
#include "sylva/bench/ViewsBenchmark.h"

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
    {"views", [](bool json) { return printMetrics("views", bench::runViewsBenchmark({}), json); }},
};

// Suites with options and structured output of their own take over the command line.
struct CommandSuite {
    const char* name;
    int (*run)(const std::vector<std::string>& arguments);
};

const CommandSuite kCommandSuites[] = {
    {"terrain", runTerrainBench},       {"tiles", runTilesBench},
    {"plantlod", runPlantLodBench},     {"turnaround", runTurnaroundBench},
    {"vegetation", runVegetationBench}, {"shading", runShadingBench},
    {"objects", runObjectsBench},       {"viewer", runViewerBench},
};

// Every suite's name, in the order `sylva bench --help` lists them.
std::string suiteNames() {
    std::string names;
    for (const Suite& suite : kSuites) {
        append(names, {names.empty() ? "" : ", ", suite.name});
    }
    for (const CommandSuite& suite : kCommandSuites) {
        append(names, {", ", suite.name});
    }
    return names;
}

}  // namespace

int runBench(const std::vector<std::string>& arguments) {
    if (!arguments.empty()) {
        for (const CommandSuite& suite : kCommandSuites) {
            if (arguments[0] == suite.name) {
                return suite.run(std::vector<std::string>(arguments.begin() + 1, arguments.end()));
            }
        }
    }
    const ParsedCommandLine command =
        parseCommandLine(arguments, {{"help", false}, {"json", false}});
    const std::string names = suiteNames();
    if (command.has("help")) {
        std::printf("usage: sylva bench SUITE [--json]\nsuites: %s\n", names.c_str());
        return 0;
    }
    if (!command.error.empty() || command.positional.size() != 1) {
        reportError(command.error.empty() ? "bench needs one suite: " + names : command.error);
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
