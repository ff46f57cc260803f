#include "sylva/bench/TurnaroundBenchmark.h"

#include <fcntl.h>
#include <sys/resource.h>
#include <sys/time.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <optional>
#include <regex>
#include <sstream>
#include <thread>

#include "sylva/core/model/BlockReader.h"
#include "sylva/core/sources/graph/SourceGraph.h"

namespace sylva::bench {
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

// Waits for `child`; its exit status, or -1. Adds its CPU seconds (user + system, all
// its threads) to `cpuSeconds` when given.
int waitFor(pid_t child, double* cpuSeconds = nullptr) {
    if (child < 0) {
        return -1;
    }
    int status = 0;
    struct rusage usage {};
    while (::wait4(child, &status, 0, &usage) < 0) {
        if (errno != EINTR) {
            return -1;
        }
    }
    if (cpuSeconds != nullptr) {
        const auto seconds = [](const timeval& t) {
            return double(t.tv_sec) + 1e-6 * double(t.tv_usec);
        };
        *cpuSeconds += seconds(usage.ru_utime) + seconds(usage.ru_stime);
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

// The view measured cold and warm: the series' first camera and first scenario (empty:
// the default).
struct FirstView {
    std::string camera;
    std::string scenario;
};

Result<FirstView> firstViewOf(const TurnaroundBenchmarkOptions& options,
                              const ProjectModel& model) {
    const Block* series = model.findViews(options.views);
    if (!series) {
        return Error{options.projectFile.string() + " has no views block '" + options.views + "'"};
    }
    BlockReader seriesReader(*series, SchemaRegistry::builtin().find("views"));
    const std::vector<std::string> cameras = seriesReader.references("cameras");
    const std::vector<std::string> scenarios = seriesReader.references("scenarios");
    if (cameras.empty()) {
        return Error{"views '" + options.views + "' has no cameras"};
    }
    return FirstView{cameras.front(), scenarios.empty() ? std::string() : scenarios.front()};
}

// Every data file the sources of any scenario read must exist (else every process
// would fail the same way, later and less clearly).
Status checkDataFiles(const TurnaroundBenchmarkOptions& options, const ProjectModel& model,
                      const std::vector<ProjectModel>& scenarios) {
    std::vector<std::filesystem::path> files;
    const auto addFilesOf = [&](const ProjectModel& scenario) {
        if (Result<SourceGraph> graph = SourceGraph::build(scenario)) {
            for (const std::filesystem::path& file : graph->files()) {
                files.push_back(file);
            }
        }
    };
    for (const ProjectModel& scenario : scenarios) {
        addFilesOf(scenario);
    }
    addFilesOf(model);
    for (const std::filesystem::path& file : files) {
        if (!std::filesystem::is_regular_file(file)) {
            return Error{"data file '" + file.string() + "' of " + options.projectFile.string() +
                         " is missing; run scripts/fetch-samples to download the samples"};
        }
    }
    return {};
}

// The edit of the warm measurement: the first `saturation = N` raised by 0.15.
Result<std::string> editedProject(const std::string& original,
                                  const std::filesystem::path& projectFile) {
    const std::regex saturation(R"((\bsaturation\s*=\s*)([0-9.]+))");
    std::smatch found;
    if (!std::regex_search(original, found, saturation)) {
        return Error{projectFile.string() +
                     " has no `saturation = N` colour adjustment to edit for warm_edit_s"};
    }
    char edited[32];
    std::snprintf(edited, sizeof edited, "%.3f", std::stod(found[2].str()) + 0.15);
    return std::string(found.prefix()) + found[1].str() + edited + std::string(found.suffix());
}

// The temporary project (the original plus a views block of the first view) and the
// output folder, removed however the benchmark ends, and the processes run on them.
class TurnaroundRun {
public:
    TurnaroundRun(const TurnaroundBenchmarkOptions& options, const FirstView& view)
        : options_(options) {
        project_ = options.projectFile.parent_path() /
                   (".turnaround-" + std::to_string(::getpid()) + ".sylva");
        folder_ = std::filesystem::temp_directory_path() /
                  ("sylva-turnaround-" + std::to_string(::getpid()));
        oneViews_ =
            "\n# added by `sylva bench turnaround`\nviews " + kOne + " {\n    cameras = [@" +
            view.camera + "]\n" +
            (view.scenario.empty() ? std::string() : "    scenarios = [@" + view.scenario + "]\n") +
            "    output = \"one.png\"\n}\n";
        common_ = {"--size", std::to_string(options.width) + "x" + std::to_string(options.height),
                   "--gl", options.gl};
    }
    ~TurnaroundRun() {
        std::error_code ignored;
        std::filesystem::remove(project_, ignored);
        std::filesystem::remove_all(folder_, ignored);
    }
    TurnaroundRun(const TurnaroundRun&) = delete;
    TurnaroundRun& operator=(const TurnaroundRun&) = delete;

    // Creates the output folder and writes the temporary project.
    Status prepare(const std::string& original) const {
        std::error_code error;
        std::filesystem::create_directories(folder_, error);
        if (error) {
            return Error{"cannot create '" + folder_.string() + "': " + error.message()};
        }
        return writeProject(original);
    }

    // Writes `text` and the added views block in place (not renamed) so the watch's
    // file stat sees one change.
    Status writeProject(const std::string& text) const {
        std::ofstream stream(project_, std::ios::trunc);
        stream << text << oneViews_;
        if (!stream) {
            return Error{"cannot write '" + project_.string() + "'"};
        }
        return {};
    }

    // 1. Cold: a fresh process for one view, without a disk cache, or (`diskCache`)
    // with one in `diskCache` (empty: the cold write; filled: the warm-disk start).
    Result<double> cold(const std::string& name = "cold",
                        const std::filesystem::path& diskCache = {}) const {
        const auto start = Clock::now();
        const std::filesystem::path log = folder_ / (name + ".log");
        if (waitFor(spawn(renderArguments(kOne, folder_ / name, diskArguments(diskCache)), log)) !=
            0) {
            return failed("the " + name + " render", log);
        }
        return secondsSince(start);
    }

    // The disk cache folders of the measurements, below the temporary folder.
    std::filesystem::path cacheFolder(const std::string& name) const { return folder_ / name; }

    // 2. Warm: watch the view, edit the colour adjustment, wait for the new image; the
    // seconds and the tiles the watch recomputed for it.
    Result<std::pair<double, double>> warm(const std::string& editedText) const {
        const std::filesystem::path log = folder_ / "watch.log";
        std::vector<std::string> arguments = {options_.executable.string(),
                                              "watch",
                                              project_.string(),
                                              "--views",
                                              kOne,
                                              "--out",
                                              (folder_ / "warm").string(),
                                              "--interval-ms",
                                              "20",
                                              "--exit-after",
                                              "2"};
        arguments.insert(arguments.end(), common_.begin(), common_.end());
        const pid_t watch = spawn(arguments, log);
        const auto stop = [watch] {
            ::kill(watch, SIGTERM);
            waitFor(watch);
        };
        if (!waitForLog(watch, log, "watching", 1, 3600)) {
            stop();
            return failed("the watch's first image", log);
        }
        const auto start = Clock::now();
        if (Status written = writeProject(editedText); !written) {
            stop();
            return Error{"cannot edit '" + project_.string() + "'"};
        }
        if (!waitForLog(watch, log, "edit-to-image latency", 2, 3600)) {
            stop();
            return failed("the watch after the edit", log);
        }
        const double seconds = secondsSince(start);
        if (waitFor(watch) != 0) {
            return failed("watch", log);
        }
        // The second "edit-to-image latency: S s, N tiles recomputed, M cached".
        const std::string text = readText(log);
        const std::regex latency(R"(edit-to-image latency: [0-9.]+ s, ([0-9]+) tiles recomputed)");
        std::vector<double> tiles;
        for (auto it = std::sregex_iterator(text.begin(), text.end(), latency);
             it != std::sregex_iterator(); ++it) {
            tiles.push_back(std::stod((*it)[1].str()));
        }
        if (tiles.size() < 2) {
            return failed("the watch (no tile count after the edit)", log);
        }
        return std::make_pair(seconds, tiles[1]);
    }

    // 3. The series in one process: its wall time and image count (and CPU seconds).
    Result<std::pair<double, std::size_t>> series(double& cpuSeconds) const {
        const auto start = Clock::now();
        if (waitFor(spawn(renderArguments(options_.views, folder_ / "series", diskArguments({})),
                          folder_ / "series.log"),
                    &cpuSeconds) != 0) {
            return failed("the series render", folder_ / "series.log");
        }
        const double seconds = secondsSince(start);
        const std::size_t images = countOf(readText(folder_ / "series.log"), " triangles, ");
        if (images == 0) {
            return failed("the series render (no images)", folder_ / "series.log");
        }
        return std::make_pair(seconds, images);
    }

    // 4. The series in two shard processes at once: their wall time and CPU seconds;
    // with `diskCache` both share that (initially empty) disk tile cache.
    Result<double> shards(double& cpuSeconds, const std::filesystem::path& diskCache = {}) const {
        const auto start = Clock::now();
        const std::string out = diskCache.empty() ? "shards" : "shards-disk";
        std::vector<std::string> firstArguments = diskArguments(diskCache);
        std::vector<std::string> secondArguments = firstArguments;
        firstArguments.insert(firstArguments.end(), {"--shard", "1/2"});
        secondArguments.insert(secondArguments.end(), {"--shard", "2/2"});
        const pid_t first = spawn(renderArguments(options_.views, folder_ / out, firstArguments),
                                  folder_ / "shard1.log");
        const pid_t second = spawn(renderArguments(options_.views, folder_ / out, secondArguments),
                                   folder_ / "shard2.log");
        const int firstStatus = waitFor(first, &cpuSeconds);
        const int secondStatus = waitFor(second, &cpuSeconds);
        const double seconds = secondsSince(start);
        if (firstStatus != 0) {
            return failed("shard 1/2", folder_ / "shard1.log");
        }
        if (secondStatus != 0) {
            return failed("shard 2/2", folder_ / "shard2.log");
        }
        return seconds;
    }

private:
    inline static const std::string kOne = "turnaround_one";

    std::vector<std::string> renderArguments(const std::string& views,
                                             const std::filesystem::path& out,
                                             const std::vector<std::string>& extra) const {
        std::vector<std::string> list = {options_.executable.string(),
                                         "render",
                                         project_.string(),
                                         "--views",
                                         views,
                                         "--out",
                                         out.string(),
                                         "--progress",
                                         "plain",
                                         "--no-comparisons"};
        list.insert(list.end(), common_.begin(), common_.end());
        list.insert(list.end(), extra.begin(), extra.end());
        return list;
    }

    // Every measurement names its disk cache: none (--no-disk-cache, so the user's
    // default cache never makes a "cold" process warm) or a folder of its own.
    static std::vector<std::string> diskArguments(const std::filesystem::path& diskCache) {
        if (diskCache.empty()) {
            return {"--no-disk-cache"};
        }
        return {"--disk-cache", diskCache.string()};
    }

    static Error failed(const std::string& what, const std::filesystem::path& log) {
        return Error{what + " failed; its output:\n" + readText(log)};
    }

    // Polls `log` until `needle` occurs `count` times; false on time-out or when the
    // watch ends first without it.
    static bool waitForLog(pid_t watch, const std::filesystem::path& log, const std::string& needle,
                           std::size_t count, double limitSeconds) {
        const auto begin = Clock::now();
        while (secondsSince(begin) < limitSeconds) {
            if (countOf(readText(log), needle) >= count) {
                return true;
            }
            int status = 0;
            if (::waitpid(watch, &status, WNOHANG) == watch) {
                return countOf(readText(log), needle) >= count;
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(5));
        }
        return false;
    }

    const TurnaroundBenchmarkOptions& options_;
    std::filesystem::path project_;
    std::filesystem::path folder_;
    std::string oneViews_;
    std::vector<std::string> common_;
};

}  // namespace

std::string TurnaroundBenchmarkResult::json() const {
    return metricsJson("turnaround", metrics, {NumberFormat::Notation::General, 4});
}

Result<TurnaroundBenchmarkResult> runTurnaroundBenchmark(
    const TurnaroundBenchmarkOptions& options, const ProjectModel& model,
    const std::vector<ProjectModel>& scenarios) {
    Result<FirstView> view = firstViewOf(options, model);
    if (!view) {
        return view.error();
    }
    if (Status present = checkDataFiles(options, model, scenarios); !present) {
        return present.error();
    }
    const std::string original = readText(options.projectFile);
    Result<std::string> edited = editedProject(original, options.projectFile);
    if (!edited) {
        return edited.error();
    }
    const TurnaroundRun run(options, view.value());
    if (Status prepared = run.prepare(original); !prepared) {
        return prepared.error();
    }
    TurnaroundBenchmarkResult result;
    const Result<double> cold = run.cold();
    if (!cold) {
        return cold.error();
    }
    result.metrics.push_back({"cold_render_s", cold.value()});
    if (!options.diskOnly) {
        const Result<std::pair<double, double>> warm = run.warm(edited.value());
        if (!warm) {
            return warm.error();
        }
        result.metrics.push_back({"warm_edit_s", warm.value().first});
        result.metrics.push_back({"edit_ratio", warm.value().first / cold.value()});
        result.metrics.push_back({"warm_edit_tiles", warm.value().second});
    }
    if (options.editOnly) {
        return result;
    }
    // The disk tile cache: a cold process writing it, then a second process reading it.
    const std::filesystem::path oneCache = run.cacheFolder("disk-cache-one");
    const Result<double> writing = run.cold("cold-disk", oneCache);
    if (!writing) {
        return writing.error();
    }
    const Result<double> reading = run.cold("warm-disk", oneCache);
    if (!reading) {
        return reading.error();
    }
    double seriesCpu = 0;
    const Result<std::pair<double, std::size_t>> series = run.series(seriesCpu);
    if (!series) {
        return series.error();
    }
    const auto [seriesSeconds, images] = series.value();
    result.images = images;
    result.metrics.push_back({"series_s_per_image", seriesSeconds / static_cast<double>(images)});
    if (!options.diskOnly) {
        double ignored = 0;
        const Result<double> shards = run.shards(ignored);
        if (!shards) {
            return shards.error();
        }
        result.metrics.push_back({"shard_speedup", seriesSeconds / shards.value()});
    }
    double shardCpu = 0;
    const Result<double> sharing = run.shards(shardCpu, run.cacheFolder("disk-cache-shards"));
    if (!sharing) {
        return sharing.error();
    }
    result.metrics.push_back({"warm_disk_start_ratio", reading.value() / cold.value()});
    result.metrics.push_back({"shard_cpu_overhead", shardCpu / seriesCpu});
    result.metrics.push_back({"cache_write_overhead", writing.value() / cold.value()});
    return result;
}

}  // namespace sylva::bench
