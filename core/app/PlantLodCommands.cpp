// `sylva plant build`, `sylva plant info` and `sylva bench plantlod`: the plant LoD
// builder (seed 001 ch. 3) on the command line.
//
// `loadPlantInput` is the one place that turns the IN argument into a PlantModel: a
// glTF/OBJ file through PlantImporter, or `--synthetic LEAVES` (tests).
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <functional>
#include <string>
#include <vector>

#include "CommandLine.h"
#include "Commands.h"
#include "ProjectSession.h"
#include "sylva/core/plants/PlantGenerator.h"
#include "sylva/core/plants/PlantImporter.h"
#include "sylva/core/plants/PlantLodBuilder.h"
#include "sylva/core/plants/PlodFile.h"
#include "sylva/core/plants/SyntheticPlant.h"

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

bool parseCount(const std::string& text, int minimum, int& out) {
    try {
        std::size_t used = 0;
        const long value = std::stol(text, &used);
        if (used != text.size() || value < minimum || value > 10'000'000) {
            return false;
        }
        out = static_cast<int>(value);
        return true;
    } catch (...) {
        return false;
    }
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
    if (const auto value = command.get("threads");
        value && !parseCount(*value, 1, options.threads)) {
        reportError("--threads needs a positive integer, got '" + *value + "'");
        return 2;
    }
    if (const auto value = command.get("synthetic"); value && !parseCount(*value, 1, synthetic)) {
        reportError("--synthetic needs a positive leaf count, got '" + *value + "'");
        return 2;
    }
    if (const auto value = command.get("seed"); value && !parseCount(*value, 0, seed)) {
        reportError("--seed needs a non-negative integer, got '" + *value + "'");
        return 2;
    }
    if (const auto value = command.get("restarts");
        value && !parseCount(*value, 1, options.restarts)) {
        reportError("--restarts needs a positive integer, got '" + *value + "'");
        return 2;
    }
    if (const auto value = command.get("ao-samples");
        value && !parseCount(*value, 0, options.ambientOcclusionSamples)) {
        reportError("--ao-samples needs a non-negative integer, got '" + *value + "'");
        return 2;
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
    const ParsedCommandLine command =
        parseCommandLine(arguments, {{"json", false}, {"threads"}, {"leaves"}, {"help", false}});
    if (command.has("help")) {
        std::puts(
            "usage: sylva bench plantlod [--json] [--threads N] [--leaves 1000,5000,10000,27000]\n"
            "builds the LoD of plants with the given leaf counts and compares with seed 001 Table "
            "3.1");
        return 0;
    }
    if (!command.error.empty() || !command.positional.empty()) {
        reportError(command.error.empty() ? "bench plantlod takes no positional arguments"
                                          : command.error);
        return 2;
    }
    PlantLodOptions options;
    if (const auto value = command.get("threads");
        value && !parseCount(*value, 1, options.threads)) {
        reportError("--threads needs a positive integer, got '" + *value + "'");
        return 2;
    }
    // Thesis precomputation times (seed 001 Table 3.1), minutes.
    struct Model {
        int leaves;
        const char* label;
        double thesisMinutes;
    };
    std::vector<Model> models = {
        {1000, "1k", 7}, {5000, "5k", 23}, {10000, "10k", 91}, {27000, "27k", 396}};
    if (const auto value = command.get("leaves")) {
        std::vector<Model> chosen;
        std::size_t start = 0;
        while (start <= value->size()) {
            const std::size_t comma = value->find(',', start);
            const std::string item = value->substr(
                start, comma == std::string::npos ? std::string::npos : comma - start);
            int leaves = 0;
            if (!parseCount(item, 1, leaves)) {
                reportError("--leaves needs comma-separated leaf counts, got '" + *value + "'");
                return 2;
            }
            bool known = false;
            for (const Model& m : models) {
                if (m.leaves == leaves) {
                    chosen.push_back(m);
                    known = true;
                }
            }
            if (!known) {
                reportError("--leaves: " + item +
                            " has no thesis time to compare with (1000, 5000, 10000, 27000)");
                return 2;
            }
            if (comma == std::string::npos) {
                break;
            }
            start = comma + 1;
        }
        models = chosen;
    }
    // The models: the generator's oak with the thesis's leaf counts (Table 3.1).
    const std::function<PlantModel(int)> makeModel = [](int leaves) {
        PlantGeneratorOptions generatorOptions;
        generatorOptions.seed = 7;
        generatorOptions.leafCount = leaves;
        Result<PlantModel> generated =
            PlantGenerator::generate(PlantGenerator::preset("oak").value(), generatorOptions);
        SYLVA_CHECK(generated.ok());
        return generated.value();
    };

    std::vector<std::pair<std::string, double>> metrics;
    double speedup = std::numeric_limits<double>::infinity();
    for (const Model& m : models) {
        const PlantModel model = makeModel(m.leaves);
        const auto start = std::chrono::steady_clock::now();
        const std::clock_t cpuStart = std::clock();
        Result<PlantLod> lod = buildPlantLod(model, options);
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        const double cpuSeconds = static_cast<double>(std::clock() - cpuStart) / CLOCKS_PER_SEC;
        if (!lod) {
            reportError(lod.error().message);
            return 1;
        }
        metrics.emplace_back(std::string("build_s_") + m.label, seconds);
        // CPU time of all threads: the machine is shared, so wall time depends on load.
        metrics.emplace_back(std::string("cpu_s_") + m.label, cpuSeconds);
        speedup = std::min(speedup, m.thesisMinutes * 60.0 / seconds);
        metrics.emplace_back(std::string("levels_") + m.label,
                             static_cast<double>(lod->levels.size()));
        metrics.emplace_back(std::string("branch_segments_") + m.label,
                             static_cast<double>(model.skeleton.size()));
        for (std::size_t k = 0; k < lod->levels.size(); ++k) {
            const std::string suffix = "_l" + std::to_string(k) + "_" + m.label;
            metrics.emplace_back("ellipsoids" + suffix, lod->levels[k].ellipsoidCount);
            metrics.emplace_back("lines" + suffix, lod->levels[k].lineCount);
            metrics.emplace_back("rmse" + suffix, lod->levels[k].imageError);
        }
        if (!command.has("json")) {
            std::fprintf(stderr, "plantlod: %s leaves in %.1f s\n", m.label, seconds);
        }
    }
    metrics.emplace_back("speedup_vs_thesis_min", speedup);
    if (command.has("json")) {
        std::string out = "{\"suite\":\"plantlod\",\"metrics\":{";
        for (std::size_t i = 0; i < metrics.size(); ++i) {
            char value[64];
            std::snprintf(value, sizeof value, "%.4f", metrics[i].second);
            out += (i ? ",\"" : "\"") + metrics[i].first + "\":" + value;
        }
        std::puts((out + "}}").c_str());
    } else {
        for (const auto& [name, value] : metrics) {
            std::printf("plantlod.%s = %.4f\n", name.c_str(), value);
        }
    }
    return 0;
}

}  // namespace sylva::app
