// `sylva bench shading [--json] [--size WxH] [--frames N] [--gl B]`: the shading suite
// (issue 16): anti-aliasing (bench/AntiAliasingBenchmark.h: aa4_frame_ratio) and the
// atmosphere (bench/AtmosphereBenchmark.h: atmosphere_ms_median, atmosphere_speedup), one
// after the other in one GL context. Prints {"suite":"shading","metrics":{...}} with
// --json, else one "shading.KEY = VALUE" line each.
#include <cstdio>
#include <string>

#include "CommandLine.h"
#include "Commands.h"
#include "ProjectSession.h"
#include "sylva/bench/AntiAliasingBenchmark.h"
#include "sylva/bench/AtmosphereBenchmark.h"
#include "sylva/bench/BenchmarkMetrics.h"
#include "sylva/render/gl/GlContext.h"

namespace sylva::app {

int runShadingBench(const std::vector<std::string>& arguments) {
    const ParsedCommandLine command =
        parseCommandLine(arguments, {{"json", false}, {"size"}, {"frames"}, {"gl"}});
    if (!command.error.empty() || !command.positional.empty()) {
        reportError(command.error.empty() ? "bench shading takes no arguments" : command.error);
        return 2;
    }
    bench::AntiAliasingBenchmarkOptions antiAliasing;
    bench::AtmosphereBenchmarkOptions atmosphere;
    if (std::optional<std::string> size = command.get("size")) {
        if (std::sscanf(size->c_str(), "%dx%d", &antiAliasing.width, &antiAliasing.height) != 2 ||
            antiAliasing.width < 16 || antiAliasing.height < 16 || antiAliasing.width > 16384 ||
            antiAliasing.height > 16384) {
            reportError("--size expects WIDTHxHEIGHT within 16..16384");
            return 2;
        }
        atmosphere.width = antiAliasing.width;
        atmosphere.height = antiAliasing.height;
    }
    const Result<std::optional<int>> frames = wholeNumberOption(
        command, "frames", 1, 1000, "expects a whole number within 1..1000", EchoValue::No);
    if (!frames) {
        reportError(frames.error().message);
        return 2;
    }
    antiAliasing.framesPerSegment = frames.value().value_or(antiAliasing.framesPerSegment);
    atmosphere.framesPerSegment = frames.value().value_or(atmosphere.framesPerSegment);
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
    bench::MetricList metrics;
    Result<bench::AntiAliasingBenchmarkResult> antiAliased =
        bench::runAntiAliasingBenchmark(render::ShaderLibrary(), antiAliasing);
    if (!antiAliased) {
        reportError(antiAliased.error().message);
        return 1;
    }
    metrics.insert(metrics.end(), antiAliased->metrics.begin(), antiAliased->metrics.end());
    Result<bench::AtmosphereBenchmarkResult> atmospheric =
        bench::runAtmosphereBenchmark(render::ShaderLibrary(), atmosphere);
    if (!atmospheric) {
        reportError(atmospheric.error().message);
        return 1;
    }
    metrics.insert(metrics.end(), atmospheric->metrics.begin(), atmospheric->metrics.end());
    if (command.has("json")) {
        std::puts(
            bench::metricsJson("shading", metrics, {bench::NumberFormat::Notation::General, 6})
                .c_str());
    } else {
        for (const auto& [name, value] : metrics) {
            std::printf("shading.%s = %.3f\n", name.c_str(), value);
        }
    }
    return 0;
}

}  // namespace sylva::app
