// `sylva bench shading [--json] [--size WxH] [--frames N] [--dem N] [--trees N] [--leaves N]
// [--gl B]`: the shading benchmark of issue 16 (bench/ShadingBenchmark.h) on the terrain
// benchmark's flight and the vegetation benchmark's forest. Prints the metrics as JSON
// with --json, else one line per metric.
#include <cstdio>

#include "CommandLine.h"
#include "Commands.h"
#include "ProjectSession.h"
#include "sylva/bench/ShadingBenchmark.h"
#include "sylva/render/gl/GlContext.h"

namespace sylva::app {

int runShadingBench(const std::vector<std::string>& arguments) {
    const ParsedCommandLine command = parseCommandLine(
        arguments, {{"json", false}, {"size"}, {"frames"}, {"dem"}, {"trees"}, {"leaves"}, {"gl"}});
    if (!command.error.empty() || !command.positional.empty()) {
        reportError(command.error.empty() ? "bench shading takes no arguments" : command.error);
        return 2;
    }
    bench::ShadingBenchmarkOptions options;
    if (std::optional<std::string> size = command.get("size")) {
        if (std::sscanf(size->c_str(), "%dx%d", &options.width, &options.height) != 2 ||
            options.width < 64 || options.height < 64) {
            reportError("--size expects WIDTHxHEIGHT (at least 64x64)");
            return 2;
        }
    }
    const auto integer = [&](const char* name, int minimum, int maximum, int& target) {
        const Result<std::optional<int>> value =
            wholeNumberOption(command, name, minimum, maximum,
                              "expects a whole number within " + std::to_string(minimum) + ".." +
                                  std::to_string(maximum),
                              EchoValue::No);
        if (!value) {
            reportError(value.error().message);
            return false;
        }
        target = value.value().value_or(target);
        return true;
    };
    int frames = options.flightFramesPerSegment;
    if (!integer("frames", 1, 100, frames) || !integer("dem", 16, 8192, options.demSamples) ||
        !integer("trees", 1, 10000000, options.trees) ||
        !integer("leaves", 50, 100000, options.leaves)) {
        return 2;
    }
    options.flightFramesPerSegment = options.forestFramesPerSegment = frames;
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
    Result<bench::ShadingBenchmarkResult> result =
        bench::runShadingBenchmark(render::ShaderLibrary(), options);
    if (!result) {
        reportError(result.error().message);
        return 1;
    }
    if (command.has("json")) {
        std::puts(result->json().c_str());
    } else {
        for (const auto& [key, value] : result->metrics) {
            std::printf("%-28s %.6g\n", key.c_str(), value);
        }
    }
    return 0;
}

}  // namespace sylva::app
