// `sylva bench turnaround [--json] [--size WxH] [--project FILE] [--views NAME]
//                         [--gl egl|osmesa|glfw]`: how fast a planner sees results on a
// real project (issue "scenarios, comparisons, series, paths, watch"), by running the
// real `sylva` binary (/proc/self/exe) on a temporary copy of the project (written next
// to it, so relative data paths hold, and removed afterwards):
//   cold_render_s       a fresh `sylva render` process for one view (first camera and
//                       scenario of the series): start-up, GL, every tile, the image;
//   warm_edit_s         `sylva watch` on that view: after its first image, a colour
//                       adjustment (`saturation` of an `adjust` source) is edited in the
//                       copy; the time from the write to the watch's new image;
//   edit_ratio          warm_edit_s / cold_render_s (target ≤ 0.3);
//   series_s_per_image  one process rendering the series (default views block
//                       `photo_points`: 3 cameras × 2 scenarios × 2 times = 12 images,
//                       --no-comparisons) divided by its image count;
//   shard_speedup       that series' wall time over the wall time of two `--shard i/2`
//                       processes started together (target ≥ 1.6).
// Default project projects/olinda/olinda.sylva at 1280×720; its data files must exist
// (scripts/fetch-samples), else a clear error. Every process starts with cold caches.
#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "CommandLine.h"
#include "Commands.h"
#include "ProjectSession.h"
#include "sylva/core/model/BlockReader.h"

namespace sylva::app {
namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

// Starts `arguments` (no shell) with stdout and stderr into `log`; -1 on failure.
pid_t spawn(const std::vector<std::string>& arguments, const std::filesystem::path& log) {
    const pid_t child = ::fork();
    if (child != 0) {
        return child;
    }
    const int file = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (file >= 0) {
        ::dup2(file, STDOUT_FILENO);
        ::dup2(file, STDERR_FILENO);
    }
    std::vector<char*> argv;
    for (const std::string& argument : arguments) {
        argv.push_back(const_cast<char*>(argument.c_str()));
    }
    argv.push_back(nullptr);
    ::execv(argv[0], argv.data());
    ::_exit(127);
}

// Waits for `child`; its exit status, or -1.
int waitFor(pid_t child) {
    if (child < 0) {
        return -1;
    }
    int status = 0;
    while (::waitpid(child, &status, 0) < 0) {
        if (errno != EINTR) {
            return -1;
        }
    }
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string readText(const std::filesystem::path& file) {
    std::ifstream stream(file);
    std::stringstream text;
    text << stream.rdbuf();
    return text.str();
}

std::size_t countOf(const std::string& text, const std::string& needle) {
    std::size_t count = 0;
    for (std::size_t at = text.find(needle); at != std::string::npos;
         at = text.find(needle, at + needle.size())) {
        ++count;
    }
    return count;
}

// Removes the temporary project and output folder however the bench ends.
struct Scratch {
    std::filesystem::path project;
    std::filesystem::path folder;
    ~Scratch() {
        std::error_code ignored;
        std::filesystem::remove(project, ignored);
        std::filesystem::remove_all(folder, ignored);
    }
};

}  // namespace

int runTurnaroundBench(const std::vector<std::string>& arguments) {
    const ParsedCommandLine command = parseCommandLine(
        arguments, {{"json", false}, {"size"}, {"project"}, {"views"}, {"gl"}, {"help", false}});
    if (command.has("help")) {
        std::puts(
            "usage: sylva bench turnaround [--json] [--size WxH] [--project FILE] [--views NAME] "
            "[--gl egl|osmesa|glfw]\n"
            "defaults: projects/olinda/olinda.sylva, views photo_points, 1280x720");
        return 0;
    }
    if (!command.error.empty() || !command.positional.empty()) {
        reportError(command.error.empty() ? "bench turnaround takes no positional arguments"
                                          : command.error);
        return 2;
    }
    const std::string size = command.get("size").value_or("1280x720");
    int width = 0, height = 0;
    if (!parseSize(size, width, height)) {
        reportError("--size expects WIDTHxHEIGHT within 1..16384, got '" + size + "'");
        return 2;
    }
    const std::string gl = command.get("gl").value_or("egl");
    const std::filesystem::path projectFile =
        command.get("project").value_or("projects/olinda/olinda.sylva");
    const std::string seriesName = command.get("views").value_or("photo_points");
    if (!std::filesystem::is_regular_file(projectFile)) {
        reportError("bench turnaround: project '" + projectFile.string() +
                    "' not found (run from the repository root or give --project FILE)");
        return 1;
    }

    // The series, its first view, and the data files it needs.
    std::optional<ProjectSession> session = ProjectSession::open(projectFile, {});
    if (!session) {
        return 1;
    }
    const Block* series = session->model.findViews(seriesName);
    if (!series) {
        reportError("bench turnaround: " + projectFile.string() + " has no views block '" +
                    seriesName + "'");
        return 1;
    }
    BlockReader seriesReader(*series, SchemaRegistry::builtin().find("views"));
    const std::vector<std::string> cameras = seriesReader.references("cameras");
    const std::vector<std::string> scenarios = seriesReader.references("scenarios");
    if (cameras.empty()) {
        reportError("bench turnaround: views '" + seriesName + "' has no cameras");
        return 1;
    }
    std::vector<std::filesystem::path> files;
    for (const Block& scenario : session->model.scenarios) {
        Result<std::pair<const ProjectModel*, SourceGraph*>> graph =
            session->forScenario(scenario.name);
        if (graph) {
            for (const std::filesystem::path& file : graph->second->files()) {
                files.push_back(file);
            }
        }
    }
    if (session->graph) {
        for (const std::filesystem::path& file : session->graph->files()) {
            files.push_back(file);
        }
    }
    for (const std::filesystem::path& file : files) {
        if (!std::filesystem::is_regular_file(file)) {
            reportError("bench turnaround: data file '" + file.string() + "' of " +
                        projectFile.string() +
                        " is missing; run scripts/fetch-samples to download the samples");
            return 1;
        }
    }
    // The edit of the warm measurement: a colour adjustment.
    const std::string original = readText(projectFile);
    const std::regex saturation(R"((\bsaturation\s*=\s*)([0-9.]+))");
    std::smatch found;
    if (!std::regex_search(original, found, saturation)) {
        reportError("bench turnaround: " + projectFile.string() +
                    " has no `saturation = N` colour adjustment to edit for warm_edit_s");
        return 1;
    }
    char edited[32];
    std::snprintf(edited, sizeof edited, "%.3f", std::stod(found[2].str()) + 0.15);
    const std::string editedText =
        std::string(found.prefix()) + found[1].str() + edited + std::string(found.suffix());

    Scratch scratch;
    scratch.project =
        projectFile.parent_path() / (".turnaround-" + std::to_string(::getpid()) + ".sylva");
    scratch.folder =
        std::filesystem::temp_directory_path() / ("sylva-turnaround-" + std::to_string(::getpid()));
    std::filesystem::create_directories(scratch.folder);
    const std::string one = "turnaround_one";
    const std::string oneViews =
        "\n# added by `sylva bench turnaround`\nviews " + one + " {\n    cameras = [@" +
        cameras.front() + "]\n" +
        (scenarios.empty() ? std::string() : "    scenarios = [@" + scenarios.front() + "]\n") +
        "    output = \"one.png\"\n}\n";
    auto writeProject = [&](const std::string& text) {
        // Written in place (not renamed) so the watch's file stat sees one change.
        std::ofstream stream(scratch.project, std::ios::trunc);
        stream << text << oneViews;
        return static_cast<bool>(stream);
    };
    if (!writeProject(original)) {
        reportError("bench turnaround: cannot write '" + scratch.project.string() + "'");
        return 1;
    }
    const std::string self = std::filesystem::read_symlink("/proc/self/exe").string();
    const std::string project = scratch.project.string();
    const std::vector<std::string> common = {"--size", size, "--gl", gl};
    auto renderArguments = [&](const std::string& views, const std::string& out,
                               std::vector<std::string> extra) {
        std::vector<std::string> list = {self,    "render",          project, "--views",
                                         views,   "--out",           out,     "--progress",
                                         "plain", "--no-comparisons"};
        list.insert(list.end(), common.begin(), common.end());
        list.insert(list.end(), extra.begin(), extra.end());
        return list;
    };
    auto failed = [&](const std::string& what, const std::filesystem::path& log) {
        reportError("bench turnaround: " + what + " failed; its output:\n" + readText(log));
        return 1;
    };

    // 1. Cold: a fresh process for one view.
    const std::filesystem::path folder = scratch.folder;
    auto start = Clock::now();
    if (waitFor(spawn(renderArguments(one, (folder / "cold").string(), {}), folder / "cold.log")) !=
        0) {
        return failed("the cold render", folder / "cold.log");
    }
    const double cold = secondsSince(start);

    // 2. Warm: watch the view, edit the colour adjustment, wait for the new image.
    const std::filesystem::path watchLog = folder / "watch.log";
    std::vector<std::string> watchArguments = {self,
                                               "watch",
                                               project,
                                               "--views",
                                               one,
                                               "--out",
                                               (folder / "warm").string(),
                                               "--interval-ms",
                                               "20",
                                               "--exit-after",
                                               "2"};
    watchArguments.insert(watchArguments.end(), common.begin(), common.end());
    const pid_t watch = spawn(watchArguments, watchLog);
    auto waitForLog = [&](const std::string& needle, std::size_t count, double limitSeconds) {
        const auto begin = Clock::now();
        while (secondsSince(begin) < limitSeconds) {
            if (countOf(readText(watchLog), needle) >= count) {
                return true;
            }
            int status = 0;
            if (::waitpid(watch, &status, WNOHANG) == watch) {
                return countOf(readText(watchLog), needle) >= count;
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(5));
        }
        return false;
    };
    if (!waitForLog("watching", 1, 3600)) {
        ::kill(watch, SIGTERM);
        waitFor(watch);
        return failed("the watch's first image", watchLog);
    }
    start = Clock::now();
    if (!writeProject(editedText)) {
        ::kill(watch, SIGTERM);
        waitFor(watch);
        reportError("bench turnaround: cannot edit '" + project + "'");
        return 1;
    }
    if (!waitForLog("edit-to-image latency", 2, 3600)) {
        ::kill(watch, SIGTERM);
        waitFor(watch);
        return failed("the watch after the edit", watchLog);
    }
    const double warm = secondsSince(start);
    if (waitFor(watch) != 0) {
        return failed("watch", watchLog);
    }

    // 3. The series in one process, 4. in two shard processes at once.
    start = Clock::now();
    if (waitFor(spawn(renderArguments(seriesName, (folder / "series").string(), {}),
                      folder / "series.log")) != 0) {
        return failed("the series render", folder / "series.log");
    }
    const double seriesSeconds = secondsSince(start);
    const std::size_t images = countOf(readText(folder / "series.log"), " triangles, ");
    if (images == 0) {
        return failed("the series render (no images)", folder / "series.log");
    }
    start = Clock::now();
    const pid_t first =
        spawn(renderArguments(seriesName, (folder / "shards").string(), {"--shard", "1/2"}),
              folder / "shard1.log");
    const pid_t second =
        spawn(renderArguments(seriesName, (folder / "shards").string(), {"--shard", "2/2"}),
              folder / "shard2.log");
    const int firstStatus = waitFor(first);
    const int secondStatus = waitFor(second);
    const double shardSeconds = secondsSince(start);
    if (firstStatus != 0) {
        return failed("shard 1/2", folder / "shard1.log");
    }
    if (secondStatus != 0) {
        return failed("shard 2/2", folder / "shard2.log");
    }

    const std::vector<std::pair<std::string, double>> metrics = {
        {"cold_render_s", cold},
        {"warm_edit_s", warm},
        {"edit_ratio", warm / cold},
        {"series_s_per_image", seriesSeconds / static_cast<double>(images)},
        {"shard_speedup", seriesSeconds / shardSeconds}};
    if (command.has("json")) {
        std::string out = "{\"suite\":\"turnaround\",\"metrics\":{";
        for (std::size_t i = 0; i < metrics.size(); ++i) {
            char buffer[160];
            std::snprintf(buffer, sizeof buffer, "%s\"%s\":%.4g", i == 0 ? "" : ",",
                          metrics[i].first.c_str(), metrics[i].second);
            out += buffer;
        }
        std::puts((out + "}}").c_str());
    } else {
        std::printf("turnaround on %s at %s (series '%s': %zu images)\n",
                    projectFile.string().c_str(), size.c_str(), seriesName.c_str(), images);
        for (const auto& [name, value] : metrics) {
            std::printf("%-20s %.4g\n", name.c_str(), value);
        }
    }
    return 0;
}

}  // namespace sylva::app
