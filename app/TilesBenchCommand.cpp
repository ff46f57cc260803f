// `sylva bench tiles [--json] [--verbose] [--cache-mb N] [--data DIR]`: the tile pipeline on the
// Olinda sample data (bench/TilesBenchmark.h: peak memory under the cache budget, default
// 64 MiB; throughput with 1 and 2 workers; reprojection against GDAL's warper; clipmap
// update bytes). Prints the metrics as JSON with --json, else one line per metric;
// --verbose adds each run's resident sets and per-source statistics on stderr.
#include <cstdio>

#include "CommandLine.h"
#include "Commands.h"
#include "ProjectSession.h"
#include "sylva/bench/TilesBenchmark.h"

namespace sylva::app {

int runTilesBench(const std::vector<std::string>& arguments) {
    const ParsedCommandLine command =
        parseCommandLine(arguments, {{"json", false}, {"verbose", false}, {"cache-mb"}, {"data"}});
    if (!command.error.empty() || !command.positional.empty()) {
        reportError(command.error.empty() ? "bench tiles takes no arguments" : command.error);
        return 2;
    }
    const Result<std::optional<std::size_t>> cacheOption = cacheMegabytesOption(command);
    if (!cacheOption) {
        reportError(cacheOption.error().message);
        return 2;
    }
    bench::TilesBenchmarkOptions options;
    options.budgetMegabytes = cacheOption.value().value_or(64);
    options.dataFolder = command.get("data").value_or("data");
    options.verbose = command.has("verbose");
    const Result<bench::TilesBenchmarkResult> result = bench::runTilesBenchmark(options);
    if (!result) {
        reportError("bench tiles: " + result.error().message);
        return 1;
    }
    if (command.has("json")) {
        std::puts(result->json().c_str());
    } else {
        for (const auto& [key, value] : result->metrics) {
            std::printf("%-32s %.6g\n", key.c_str(), value);
        }
    }
    return 0;
}

}  // namespace sylva::app
