// `sylva plant build`, `sylva plant info` and `sylva bench plantlod`: the plant LoD
// builder (seed 001 ch. 3) on the command line (the benchmark's body is
// bench/PlantLodBenchmark.h).
//
// `loadPlantInput` is the one place that turns the IN argument into a PlantModel: a
// glTF/OBJ file through PlantImporter, or `--synthetic LEAVES` (tests).
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "CommandLine.h"
#include "Commands.h"
#include "ProjectSession.h"
#include "sylva/bench/PlantLodBenchmark.h"
#include "sylva/core/plantlod/PlantImporter.h"
#include "sylva/core/plantlod/PlantLodBuilder.h"
#include "sylva/core/plantlod/PlodFile.h"
#include "sylva/core/plantlod/SyntheticPlant.h"

namespace sylva::app {

namespace {

// Replaces `-o X` by `--out X` (the short form the usage promises).
std::vector<std::string> expandShortOptions(std::vector<std::string> arguments) {
    for (std::string& argument : arguments) {
        if (argument == "-o") {
            argument = "--out";
        }
    }
    return arguments;
}

// The largest count any of these options takes.
constexpr long kMaximumCount = 10'000'000;

// `--leaves 1000,5000,...`: the models of seed 001 Table 3.1 with these leaf counts, in
// the order given; the first item that is no count or has no thesis time is the error.
Result<std::vector<bench::ThesisPlantModel>> thesisModelsOption(const std::string& value) {
    std::vector<bench::ThesisPlantModel> chosen;
    std::size_t start = 0;
    while (start <= value.size()) {
        const std::size_t comma = value.find(',', start);
        const std::string item =
            value.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
        const std::optional<int> leaves = parseWholeNumber(item, 1, kMaximumCount);
        if (!leaves) {
            return Error{"--leaves needs comma-separated leaf counts, got '" + value + "'"};
        }
        const std::optional<bench::ThesisPlantModel> model = bench::thesisPlantModel(*leaves);
        if (!model) {
            return Error{"--leaves: " + item +
                         " has no thesis time to compare with (1000, 5000, 10000, 27000)"};
        }
        chosen.push_back(*model);
        if (comma == std::string::npos) {
            break;
        }
        start = comma + 1;
    }
    return chosen;
}

Result<PlantModel> loadPlantInput(const std::string& input, int syntheticLeaves,
                                  std::uint32_t seed) {
    if (syntheticLeaves > 0) {
        return makeSyntheticPlant(syntheticLeaves, seed);
    }
    return PlantImporter::import(input);
}

std::string formatDuration(double seconds) {
    const int s = static_cast<int>(std::lround(std::max(seconds, 0.0)));
    char text[32];
    std::snprintf(text, sizeof text, "%d:%02d", s / 60, s % 60);
    return text;
}

// A progress bar on a terminal, one line per stage otherwise.
class ProgressPrinter {
public:
    ProgressPrinter()
        : tty_(::isatty(fileno(stderr)) != 0), start_(std::chrono::steady_clock::now()) {}
    ~ProgressPrinter() {
        if (tty_ && drawn_) {
            std::fputc('\n', stderr);
        }
    }

    void operator()(const PlantLodProgress& p) {
        const double elapsed =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
        if (!tty_) {
            if (p.stage != lastStage_) {
                std::fprintf(stderr, "plant build: %s (%.1f s, %.1f s CPU)\n", p.stage.c_str(),
                             elapsed, static_cast<double>(std::clock()) / CLOCKS_PER_SEC);
                lastStage_ = p.stage;
            }
            return;
        }
        const int width = 30;
        const int filled = static_cast<int>(p.fraction * width);
        std::string bar(static_cast<std::size_t>(filled), '#');
        bar.append(static_cast<std::size_t>(width - filled), ' ');
        std::string detail;
        if (p.levelCount > 0) {
            detail += (p.stage == "lines" ? " merge " : " level ") + std::to_string(p.level) + "/" +
                      std::to_string(p.levelCount);
        }
        if (p.restartCount > 0) {
            detail +=
                " restart " + std::to_string(p.restart) + "/" + std::to_string(p.restartCount);
        }
        const std::string eta = p.fraction > 0.02
                                    ? formatDuration(elapsed * (1.0 - p.fraction) / p.fraction)
                                    : std::string("?");
        std::fprintf(stderr, "\r[%s] %3d%% %-18s%-28s ETA %s   ", bar.c_str(),
                     static_cast<int>(p.fraction * 100), p.stage.c_str(), detail.c_str(),
                     eta.c_str());
        std::fflush(stderr);
        drawn_ = true;
    }

private:
    bool tty_;
    bool drawn_ = false;
    std::string lastStage_;
    std::chrono::steady_clock::time_point start_;
};

std::string formatError(float e) {
    if (std::isinf(e)) {
        return "inf";
    }
    char text[32];
    std::snprintf(text, sizeof text, "%.4g", e);
    return text;
}

}  // namespace

int runPlantBuild(const std::vector<std::string>& rawArguments) {
    const ParsedCommandLine command =
        parseCommandLine(expandShortOptions(rawArguments), {{"out"},
                                                            {"threads"},
                                                            {"synthetic"},
                                                            {"seed"},
                                                            {"restarts"},
                                                            {"ao-samples"},
                                                            {"bbc", false},
                                                            {"help", false}});
    if (command.has("help")) {
        std::puts(
            "usage: sylva plant build (IN | --synthetic LEAVES) -o OUT.plod [--threads N] [--seed "
            "N]\n"
            "                         [--restarts N] [--ao-samples N] [--bbc]\n"
            "builds the ellipsoid/line LoD of a plant (seed 001 ch. 3) into a .plod file;\n"
            "--bbc adds billboard clouds (seed 003) for comparison");
        return 0;
    }
    if (!command.error.empty()) {
        reportError(command.error);
        return 2;
    }
    PlantLodOptions options;
    int synthetic = 0;
    int seed = 1;
    // The option, its target, the smallest value and the usage error's requirement.
    const struct {
        const char* name;
        int& target;
        long minimum;
        const char* requirement;
    } counts[] = {
        {"threads", options.threads, 1, "needs a positive integer"},
        {"synthetic", synthetic, 1, "needs a positive leaf count"},
        {"seed", seed, 0, "needs a non-negative integer"},
        {"restarts", options.restarts, 1, "needs a positive integer"},
        {"ao-samples", options.ambientOcclusionSamples, 0, "needs a non-negative integer"}};
    for (const auto& count : counts) {
        const Result<std::optional<int>> value =
            wholeNumberOption(command, count.name, count.minimum, kMaximumCount, count.requirement);
        if (!value) {
            reportError(value.error().message);
            return 2;
        }
        count.target = value.value().value_or(count.target);
    }
    options.seed = static_cast<std::uint32_t>(seed);
    const bool hasInput = command.positional.size() == 1;
    if ((hasInput == (synthetic > 0)) || command.positional.size() > 1) {
        reportError("plant build needs exactly one input: a model file or --synthetic LEAVES");
        return 2;
    }
    const auto out = command.get("out");
    if (!out || out->empty()) {
        reportError("plant build needs -o OUT.plod");
        return 2;
    }
    Result<PlantModel> model =
        loadPlantInput(hasInput ? command.positional[0] : "", synthetic, options.seed);
    if (!model) {
        reportError(model.error().message);
        return 1;
    }
    Result<PlantLod> lod = [&] {
        ProgressPrinter printer;
        return buildPlantLod(*model, options, std::ref(printer));
    }();
    if (!lod) {
        reportError(lod.error().message);
        return 1;
    }
    if (command.has("bbc")) {
        std::fprintf(stderr, "plant build: billboard clouds\n");
        if (Status built = addBillboardClouds(*model, *lod, options); !built) {
            reportError(built.error().message);
            return 1;
        }
    }
    if (Status written = writePlodFile(*lod, *out); !written) {
        reportError(written.error().message);
        return 1;
    }
    std::printf("wrote %s: %zu levels, %zu ellipsoids, %zu lines, %zu billboard levels\n",
                out->c_str(), lod->levels.size(), lod->ellipsoids.size(), lod->lines.size(),
                lod->billboards.levels.size());
    return 0;
}

int runPlantInfo(const std::vector<std::string>& arguments) {
    const ParsedCommandLine command = parseCommandLine(arguments, {{"help", false}});
    if (command.has("help")) {
        std::puts(
            "usage: sylva plant info FILE.plod\nprints levels, primitive counts, errors and bytes");
        return 0;
    }
    if (!command.error.empty() || command.positional.size() != 1) {
        reportError(command.error.empty() ? "plant info needs one .plod file" : command.error);
        return 2;
    }
    PlodFileInfo info;
    Result<PlantLod> lod = readPlodFile(command.positional[0], &info);
    if (!lod) {
        reportError(lod.error().message);
        return 1;
    }
    std::printf("%s: plant '%s', .plod version %u, %llu bytes\n", command.positional[0].c_str(),
                lod->name.c_str(), info.version, static_cast<unsigned long long>(info.fileSize));
    std::printf("bounds: (%.3f, %.3f, %.3f) – (%.3f, %.3f, %.3f) m\n", lod->boundsMinimum.x,
                lod->boundsMinimum.y, lod->boundsMinimum.z, lod->boundsMaximum.x,
                lod->boundsMaximum.y, lod->boundsMaximum.z);
    std::printf("sections:\n");
    for (const PlodSectionInfo& s : info.sections) {
        std::printf("  %s  %8u × %3u bytes = %10llu bytes at %llu\n", s.tag.c_str(), s.count,
                    s.stride, static_cast<unsigned long long>(s.size),
                    static_cast<unsigned long long>(s.offset));
    }
    std::printf("level  error range (m/px)        ellipsoids  lines  rmse     alpha  scale\n");
    for (std::size_t k = 0; k < lod->levels.size(); ++k) {
        const PlantLodLevel& l = lod->levels[k];
        std::printf("%5zu  [%9s, %9s)  %10u  %5u  %.5f  %.2f   %.3f\n", k,
                    formatError(l.errorMinimum).c_str(), formatError(l.errorMaximum).c_str(),
                    l.ellipsoidCount, l.lineCount, l.imageError, l.alphaThreshold,
                    l.primitiveScale);
    }
    if (!lod->billboards.levels.empty()) {
        std::printf("billboard level  epsilon (m)  planes  atlas        bytes  rmse\n");
        for (std::size_t k = 0; k < lod->billboards.levels.size(); ++k) {
            const BillboardLevel& b = lod->billboards.levels[k];
            char atlas[32];
            std::snprintf(atlas, sizeof atlas, "%dx%d", b.atlas.width, b.atlas.height);
            std::printf("%15zu  %11.3f  %6zu  %-9s  %8llu  %.5f\n", k, b.epsilon, b.quads.size(),
                        atlas, static_cast<unsigned long long>(b.byteSize()), b.imageError);
        }
    }
    return 0;
}

int runPlantLodBench(const std::vector<std::string>& arguments) {
    const ParsedCommandLine command = parseCommandLine(arguments, {{"json", false},
                                                                   {"threads"},
                                                                   {"leaves"},
                                                                   {"montage"},
                                                                   {"no-billboards", false},
                                                                   {"help", false}});
    if (command.has("help")) {
        std::puts(
            "usage: sylva bench plantlod [--json] [--threads N] [--leaves 1000,5000,10000,27000]\n"
            "                            [--no-billboards] [--montage IMAGE.png]\n"
            "builds the LoD of plants with the given leaf counts and compares with seed 001 Table "
            "3.1;\nbillboard clouds of the same models for the equal-memory comparison (Fig. "
            "3.19);\n--montage writes every level beside the source, one row per model and per "
            "preset");
        return 0;
    }
    if (!command.error.empty() || !command.positional.empty()) {
        reportError(command.error.empty() ? "bench plantlod takes no positional arguments"
                                          : command.error);
        return 2;
    }
    bench::PlantLodBenchmarkOptions options;
    const Result<std::optional<int>> threads =
        wholeNumberOption(command, "threads", 1, kMaximumCount, "needs a positive integer");
    if (!threads) {
        reportError(threads.error().message);
        return 2;
    }
    options.lod.threads = threads.value().value_or(options.lod.threads);
    if (const auto value = command.get("leaves")) {
        Result<std::vector<bench::ThesisPlantModel>> models = thesisModelsOption(*value);
        if (!models) {
            reportError(models.error().message);
            return 2;
        }
        options.models = std::move(models.value());
    }
    options.billboards = !command.has("no-billboards");
    options.montagePath = command.get("montage").value_or("");
    options.reportProgress = !command.has("json");
    const Result<bench::PlantLodBenchmarkResult> result = bench::runPlantLodBenchmark(options);
    if (!result) {
        reportError(result.error().message);
        return 1;
    }
    if (command.has("json")) {
        std::puts(result->json().c_str());
    } else {
        for (const auto& [name, value] : result->metrics) {
            std::printf("plantlod.%s = %.4f\n", name.c_str(), value);
        }
    }
    return 0;
}

}  // namespace sylva::app
