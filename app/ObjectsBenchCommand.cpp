// `sylva bench objects [--json] [--size WxH] [--buildings N] [--turbines N] [--frames N]
// [--cache-mb N] [--gl B]`: the proposal's benchmark (bench/ObjectsBenchmark.h): a generated city
// of extruded footprints and a wind farm of instanced turbines on the terrain benchmark's flight,
// against the terrain alone.
#include <cstdio>

#include "CommandLine.h"
#include "Commands.h"
#include "ProjectSession.h"
#include "sylva/bench/ObjectsBenchmark.h"
#include "sylva/render/gl/GlContext.h"

namespace sylva::app {

int runObjectsBench(const std::vector<std::string>& arguments) {
    const ParsedCommandLine command = parseCommandLine(
        arguments,
        {{"json", false}, {"size"}, {"buildings"}, {"turbines"}, {"frames"}, {"cache-mb"}, {"gl"}});
    if (!command.error.empty() || !command.positional.empty()) {
        reportError(command.error.empty() ? "bench objects takes no arguments" : command.error);
        return 2;
    }
    bench::ObjectsBenchmarkOptions options;
    if (std::optional<std::string> size = command.get("size")) {
        if (std::sscanf(size->c_str(), "%dx%d", &options.width, &options.height) != 2 ||
            options.width < 16 || options.height < 16) {
            reportError("--size expects WIDTHxHEIGHT");
            return 2;
        }
    }
    struct Count {
        const char* name;
        int minimum, maximum;
        int* target;
    };
    for (const Count& count : {Count{"buildings", 1, 1000000, &options.buildings},
                               Count{"turbines", 1, 100000, &options.turbines},
                               Count{"frames", 1, 1000, &options.framesPerSegment}}) {
        const Result<std::optional<int>> value =
            wholeNumberOption(command, count.name, count.minimum, count.maximum,
                              "expects a whole number within " + std::to_string(count.minimum) +
                                  ".." + std::to_string(count.maximum),
                              EchoValue::No);
        if (!value) {
            reportError(value.error().message);
            return 2;
        }
        *count.target = value.value().value_or(*count.target);
    }
    const Result<std::optional<std::size_t>> cache = cacheMegabytesOption(command);
    if (!cache) {
        reportError(cache.error().message);
        return 2;
    }
    options.cacheMegabytes = cache.value().value_or(options.cacheMegabytes);
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
    Result<bench::ObjectsBenchmarkResult> result =
        bench::runObjectsBenchmark(render::ShaderLibrary(), options);
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
    }
    return 0;
}

}  // namespace sylva::app
