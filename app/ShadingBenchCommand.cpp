// `sylva bench shading [--json] [--size WxH] [--frames N] [--gl B]`: the shading suite
// (bench/AtmosphereBenchmark.h: atmosphere_ms_median, atmosphere_speedup). Prints the
// metrics as JSON with --json, else one line per metric.
#include <cstdio>

#include "CommandLine.h"
#include "Commands.h"
#include "ProjectSession.h"
#include "sylva/bench/AtmosphereBenchmark.h"
#include "sylva/render/gl/GlContext.h"

namespace sylva::app {

int runShadingBench(const std::vector<std::string>& arguments) {
    const ParsedCommandLine command =
        parseCommandLine(arguments, {{"json", false}, {"size"}, {"frames"}, {"gl"}});
    if (!command.error.empty() || !command.positional.empty()) {
        reportError(command.error.empty() ? "bench shading takes no arguments" : command.error);
        return 2;
    }
    bench::AtmosphereBenchmarkOptions options;
    if (std::optional<std::string> size = command.get("size")) {
        if (std::sscanf(size->c_str(), "%dx%d", &options.width, &options.height) != 2 ||
            options.width < 16 || options.height < 16) {
            reportError("--size expects WIDTHxHEIGHT");
            return 2;
        }
    }
    const Result<std::optional<int>> frames = wholeNumberOption(
        command, "frames", 1, 1000, "expects a whole number within 1..1000", EchoValue::No);
    if (!frames) {
        reportError(frames.error().message);
        return 2;
    }
    options.framesPerSegment = frames.value().value_or(options.framesPerSegment);
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
    Result<bench::AtmosphereBenchmarkResult> result =
        bench::runAtmosphereBenchmark(render::ShaderLibrary(), options);
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
