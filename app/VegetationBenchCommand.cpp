// `sylva bench vegetation [--json] [--size WxH] [--trees N] [--leaves N] [--frames N]
// [--reference-scale N] [--no-scaling] [--no-occlusion]
// [--methods lod,bbc,mesh,points,dmbbc,impostors,farfield] [--write-frames DIR] [--gl B]`: the
// vegetation renderer benchmark of issue 7 (bench/VegetationBenchmark.h). Prints the metrics as
// JSON with --json, else one line per metric. `farfield` is the far-field canopy's pass
// (bench/FarFieldBenchmark.h; part of the default run).
#include <cstdio>

#include "CommandLine.h"
#include "Commands.h"
#include "ProjectSession.h"
#include "sylva/bench/VegetationBenchmark.h"
#include "sylva/render/gl/GlContext.h"

namespace sylva::app {

int runVegetationBench(const std::vector<std::string>& arguments) {
    const ParsedCommandLine command = parseCommandLine(arguments, {{"json", false},
                                                                   {"size"},
                                                                   {"trees"},
                                                                   {"leaves"},
                                                                   {"frames"},
                                                                   {"reference-scale"},
                                                                   {"no-scaling", false},
                                                                   {"no-occlusion", false},
                                                                   {"methods"},
                                                                   {"write-frames"},
                                                                   {"gl"}});
    if (!command.error.empty() || !command.positional.empty()) {
        reportError(command.error.empty() ? "bench vegetation takes no arguments" : command.error);
        return 2;
    }
    bench::VegetationBenchmarkOptions options;
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
    if (!integer("trees", 1, 10000000, options.trees) ||
        !integer("leaves", 50, 100000, options.leaves) ||
        !integer("frames", 1, 100, options.framesPerSegment) ||
        !integer("reference-scale", 1, 8, options.referenceScale)) {
        return 2;
    }
    options.scaling = !command.has("no-scaling");
    options.occlusion = !command.has("no-occlusion");
    if (std::optional<std::string> methods = command.get("methods")) {
        options.lod = options.billboards = options.mesh = options.farField = false;
        options.points = options.dmbbc = false;
        options.impostors = false;
        std::size_t start = 0;
        while (start <= methods->size()) {
            const std::size_t end = std::min(methods->find(',', start), methods->size());
            const std::string method = methods->substr(start, end - start);
            if (method == "lod") {
                options.lod = true;
            } else if (method == "bbc") {
                options.billboards = true;
            } else if (method == "mesh") {
                options.mesh = true;
            } else if (method == "points") {
                options.points = true;
            } else if (method == "dmbbc") {
                options.dmbbc = true;
            } else if (method == "impostors") {
                options.impostors = true;
            } else if (method == "farfield") {
                options.farField = true;
            } else {
                reportError(
                    "--methods expects a comma-separated list of lod, bbc, mesh, points, dmbbc, "
                    "impostors and farfield (got '" +
                    method + "')");
                return 2;
            }
            start = end + 1;
        }
    }
    options.framesFolder = command.get("write-frames").value_or("");
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
    Result<bench::VegetationBenchmarkResult> result =
        bench::runVegetationBenchmark(render::ShaderLibrary(), options);
    if (!result) {
        reportError(result.error().message);
        return 1;
    }
    if (command.has("json")) {
        std::puts(result->json().c_str());
    } else {
        for (const auto& [key, value] : result->metrics) {
            std::printf("%-24s %.6g\n", key.c_str(), value);
        }
    }
    return 0;
}

}  // namespace sylva::app
