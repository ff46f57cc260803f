// `sylva bench shading [--json] [--only PARTS] [--size WxH] [--frames N] [--dem N] [--trees N]
// [--leaves N] [--moving-frames N] [--shadow-margin F] [--gl B]`: the shading suite of issue 16,
// one part after the other in one GL context: anti-aliasing (bench/AntiAliasingBenchmark.h:
// aa4_frame_ratio), the atmosphere (bench/AtmosphereBenchmark.h: atmosphere_ms_median,
// atmosphere_speedup) and sun shadows on the terrain flight and the vegetation forest, with
// screen-space ambient occlusion on the same frames (bench/ShadingBenchmark.h: shadow_frame_ratio,
// ssao_frame_ratio), and with a moving camera (`--moving-frames` per stretch, 0: none;
// `--shadow-margin` overrides ShadowSettings::recentreMargin, 0 for texel snapping alone:
// shadow_frame_ratio_moving). `--only` takes a comma-separated subset of
// antialiasing,atmosphere,shadows. Prints {"suite":"shading","metrics":{...}} with --json,
// else one "shading.KEY = VALUE" line each.
#include <cstdio>
#include <set>
#include <sstream>
#include <string>

#include "CommandLine.h"
#include "Commands.h"
#include "ProjectSession.h"
#include "sylva/bench/AntiAliasingBenchmark.h"
#include "sylva/bench/AtmosphereBenchmark.h"
#include "sylva/bench/BenchmarkMetrics.h"
#include "sylva/bench/ShadingBenchmark.h"
#include "sylva/render/gl/GlContext.h"

namespace sylva::app {
namespace {

struct ShadingOptions {
    std::set<std::string> parts{"antialiasing", "atmosphere", "shadows"};
    bench::AntiAliasingBenchmarkOptions antiAliasing;
    bench::AtmosphereBenchmarkOptions atmosphere;
    bench::ShadingBenchmarkOptions shadows;
};

// Reads the options into `options`; false (after reporting) on a usage error.
bool readShadingOptions(const ParsedCommandLine& command, ShadingOptions& options) {
    if (std::optional<std::string> only = command.get("only")) {
        options.parts.clear();
        std::stringstream list(*only);
        for (std::string part; std::getline(list, part, ',');) {
            if (part != "antialiasing" && part != "atmosphere" && part != "shadows") {
                reportError("--only expects antialiasing, atmosphere or shadows, got '" + part +
                            "'");
                return false;
            }
            options.parts.insert(part);
        }
    }
    if (std::optional<std::string> size = command.get("size")) {
        int width = 0;
        int height = 0;
        if (std::sscanf(size->c_str(), "%dx%d", &width, &height) != 2 || width < 16 ||
            height < 16 || width > 16384 || height > 16384) {
            reportError("--size expects WIDTHxHEIGHT within 16..16384");
            return false;
        }
        options.antiAliasing.width = options.atmosphere.width = options.shadows.width = width;
        options.antiAliasing.height = options.atmosphere.height = options.shadows.height = height;
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
    int frames = 0;
    if (!integer("frames", 1, 1000, frames) ||
        !integer("dem", 16, 8192, options.shadows.demSamples) ||
        !integer("trees", 1, 10000000, options.shadows.trees) ||
        !integer("leaves", 50, 100000, options.shadows.leaves) ||
        !integer("moving-frames", 0, 1000, options.shadows.movingFrames)) {
        return false;
    }
    if (std::optional<std::string> margin = command.get("shadow-margin")) {
        double value = -1.0;
        char rest = 0;
        if (std::sscanf(margin->c_str(), "%lf%c", &value, &rest) != 1 || !(value >= 0.0) ||
            value > 1.0) {
            reportError("--shadow-margin expects a number within 0..1");
            return false;
        }
        options.shadows.shadowMargin = value;
    }
    if (frames > 0) {
        options.antiAliasing.framesPerSegment = options.atmosphere.framesPerSegment = frames;
        options.shadows.flightFramesPerSegment = options.shadows.forestFramesPerSegment = frames;
    }
    return true;
}

// Runs the chosen parts; appends their metrics.
Status runShadingParts(const ShadingOptions& options, bench::MetricList& metrics) {
    const render::ShaderLibrary library;
    if (options.parts.count("antialiasing")) {
        Result<bench::AntiAliasingBenchmarkResult> result =
            bench::runAntiAliasingBenchmark(library, options.antiAliasing);
        if (!result) {
            return result.error();
        }
        metrics.insert(metrics.end(), result->metrics.begin(), result->metrics.end());
    }
    if (options.parts.count("atmosphere")) {
        Result<bench::AtmosphereBenchmarkResult> result =
            bench::runAtmosphereBenchmark(library, options.atmosphere);
        if (!result) {
            return result.error();
        }
        metrics.insert(metrics.end(), result->metrics.begin(), result->metrics.end());
    }
    if (options.parts.count("shadows")) {
        Result<bench::ShadingBenchmarkResult> result =
            bench::runShadingBenchmark(library, options.shadows);
        if (!result) {
            return result.error();
        }
        metrics.insert(metrics.end(), result->metrics.begin(), result->metrics.end());
    }
    return Status::success();
}

}  // namespace

int runShadingBench(const std::vector<std::string>& arguments) {
    const ParsedCommandLine command = parseCommandLine(arguments, {{"json", false},
                                                                   {"only"},
                                                                   {"size"},
                                                                   {"frames"},
                                                                   {"dem"},
                                                                   {"trees"},
                                                                   {"leaves"},
                                                                   {"moving-frames"},
                                                                   {"shadow-margin"},
                                                                   {"gl"}});
    if (!command.error.empty() || !command.positional.empty()) {
        reportError(command.error.empty() ? "bench shading takes no arguments" : command.error);
        return 2;
    }
    ShadingOptions options;
    if (!readShadingOptions(command, options)) {
        return 2;
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
    bench::MetricList metrics;
    if (Status ran = runShadingParts(options, metrics); !ran) {
        reportError(ran.error().message);
        return 1;
    }
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
