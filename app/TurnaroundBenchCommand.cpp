// `sylva bench turnaround [--json] [--size WxH] [--project FILE] [--views NAME]
//                         [--gl egl|osmesa|glfw] [--disk-only | --edit-only]`: how fast a planner
//                         sees results on
//                         a
// real project (bench/TurnaroundBenchmark.h: cold render, warm edit through `watch`,
// series per image, shard speedup, the disk tile cache's keys), measured by running this very
// binary
// (/proc/self/exe) as child processes. Default project projects/olinda/olinda.sylva at
// 1280×720, views photo_points; its data files must exist (scripts/fetch-samples), else
// a clear error.
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <system_error>

#include "CommandLine.h"
#include "Commands.h"
#include "ProjectSession.h"
#include "sylva/bench/TurnaroundBenchmark.h"

namespace sylva::app {

int runTurnaroundBench(const std::vector<std::string>& arguments) {
    const ParsedCommandLine command = parseCommandLine(arguments, {{"json", false},
                                                                   {"size"},
                                                                   {"project"},
                                                                   {"views"},
                                                                   {"gl"},
                                                                   {"disk-only", false},
                                                                   {"edit-only", false},
                                                                   {"help", false}});
    if (command.has("help")) {
        std::puts(
            "usage: sylva bench turnaround [--json] [--size WxH] [--project FILE] [--views NAME] "
            "[--gl egl|osmesa|glfw] [--disk-only | --edit-only]\n"
            "defaults: projects/olinda/olinda.sylva, views photo_points, 1280x720\n"
            "--disk-only: the reduced mode (cold render, series and the disk cache keys; no\n"
            "warm edit, no shard speedup)\n"
            "--edit-only: cold render and warm edit only (cold_render_s, warm_edit_s,\n"
            "edit_ratio, warm_edit_tiles)");
        return 0;
    }
    if (!command.error.empty() || !command.positional.empty()) {
        reportError(command.error.empty() ? "bench turnaround takes no positional arguments"
                                          : command.error);
        return 2;
    }
    bench::TurnaroundBenchmarkOptions options;
    const std::string size = command.get("size").value_or("1280x720");
    if (!parseSize(size, options.width, options.height)) {
        reportError("--size expects WIDTHxHEIGHT within 1..16384, got '" + size + "'");
        return 2;
    }
    options.gl = command.get("gl").value_or("egl");
    options.projectFile = command.get("project").value_or("projects/olinda/olinda.sylva");
    options.views = command.get("views").value_or("photo_points");
    options.diskOnly = command.has("disk-only");
    options.editOnly = command.has("edit-only");
    if (options.diskOnly && options.editOnly) {
        reportError("bench turnaround: --disk-only and --edit-only exclude each other");
        return 2;
    }
    if (!std::filesystem::is_regular_file(options.projectFile)) {
        reportError("bench turnaround: project '" + options.projectFile.string() +
                    "' not found (run from the repository root or give --project FILE)");
        return 1;
    }
    // The processes measured run this binary.
    std::error_code error;
    options.executable = std::filesystem::read_symlink("/proc/self/exe", error);
    if (error) {
        reportError("bench turnaround: cannot find the running sylva binary (/proc/self/exe): " +
                    error.message());
        return 1;
    }
    std::optional<ProjectSession> session = ProjectSession::open(options.projectFile, {});
    if (!session) {
        return 1;
    }
    const Result<bench::TurnaroundBenchmarkResult> result =
        bench::runTurnaroundBenchmark(options, session->model, session->graphs->models());
    if (!result) {
        reportError("bench turnaround: " + result.error().message);
        return 1;
    }
    if (command.has("json")) {
        std::puts(result->json().c_str());
    } else {
        std::printf("turnaround on %s at %s (series '%s': %zu images)\n",
                    options.projectFile.string().c_str(), size.c_str(), options.views.c_str(),
                    result->images);
        for (const auto& [name, value] : result->metrics) {
            std::printf("%-20s %.4g\n", name.c_str(), value);
        }
    }
    return 0;
}

}  // namespace sylva::app
