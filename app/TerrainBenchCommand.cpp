// `sylva bench terrain [--json] [--size WxH] [--dem N] [--frames N] [--gl B]
// [--write-frames DIR] [--wait-for-tiles] [--cache-mb N]`: the spherical clipmap flight benchmark
// (bench/TerrainBenchmark.h). Prints the metrics as JSON with --json, else one line
// per metric; --write-frames keeps the flight as a PNG sequence to look at.
#include <cstdio>

#include "CommandLine.h"
#include "Commands.h"
#include "ProjectSession.h"
#include "sylva/bench/TerrainBenchmark.h"
#include "sylva/render/gl/GlContext.h"

namespace sylva::app {

int runTerrainBench(const std::vector<std::string>& arguments) {
    const ParsedCommandLine command = parseCommandLine(arguments, {{"json", false},
                                                                   {"size"},
                                                                   {"dem"},
                                                                   {"frames"},
                                                                   {"gl"},
                                                                   {"write-frames"},
                                                                   {"wait-for-tiles", false},
                                                                   {"cache-mb"}});
    if (!command.error.empty() || !command.positional.empty()) {
        reportError(command.error.empty() ? "bench terrain takes no arguments" : command.error);
        return 2;
    }
    bench::TerrainBenchmarkOptions options;
    if (std::optional<std::string> size = command.get("size")) {
        if (std::sscanf(size->c_str(), "%dx%d", &options.width, &options.height) != 2 ||
            options.width < 16 || options.height < 16) {
            reportError("--size expects WIDTHxHEIGHT");
            return 2;
        }
    }
    const Result<std::optional<int>> dem = wholeNumberOption(
        command, "dem", 16, 8192, "expects a sample count per side within 16..8192", EchoValue::No);
    if (!dem) {
        reportError(dem.error().message);
        return 2;
    }
    options.demSamples = dem.value().value_or(options.demSamples);
    const Result<std::optional<int>> frames = wholeNumberOption(
        command, "frames", 1, 10000, "expects a whole number within 1..10000", EchoValue::No);
    if (!frames) {
        reportError(frames.error().message);
        return 2;
    }
    options.framesPerSegment = frames.value().value_or(options.framesPerSegment);
    options.framesFolder = command.get("write-frames").value_or("");
    options.waitForTiles = command.has("wait-for-tiles");
    const Result<std::optional<std::size_t>> cacheOption = cacheMegabytesOption(command);
    if (!cacheOption) {
        reportError(cacheOption.error().message);
        return 2;
    }
    if (cacheOption.value()) {
        options.cacheBytes = *cacheOption.value() << 20;
    }
    render::ContextOptions contextOptions;
    Result<std::optional<render::GlBackend>> backend = glBackendOption(command);
    if (!backend) {
        reportError(backend.error().message);
        return 2;
    }
    contextOptions.backend = backend.value();
    Result<std::unique_ptr<render::GlContext>> context = render::GlContext::create(contextOptions);
    if (!context) {
        reportError(context.error().message);
        return 1;
    }
    Result<bench::TerrainBenchmarkResult> result =
        bench::runTerrainBenchmark(render::ShaderLibrary(), options);
    if (!result) {
        reportError(result.error().message);
        return 1;
    }
    if (command.has("json")) {
        std::puts(result->json().c_str());
    } else {
        for (const auto& [key, value] : result->metrics) {
            std::printf("%-32s %.6g\n", key.c_str(), value);
        }
        for (const auto& [altitude, levels] : result->levelsPerAltitude) {
            std::printf("levels at %10.0f m: %d-%d\n", altitude, levels.first, levels.second);
        }
    }
    return 0;
}

}  // namespace sylva::app
