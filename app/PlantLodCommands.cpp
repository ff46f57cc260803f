// `sylva plant build`, `sylva plant info` and `sylva bench plantlod`: the plant LoD
// builder (seed 001 ch. 3) on the command line.
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
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "CommandLine.h"
#include "Commands.h"
#include "ProjectSession.h"
#include "sylva/core/image/ImageWriter.h"
#include "sylva/core/plantlod/PlantGenerator.h"
#include "sylva/core/plantlod/PlantImporter.h"
#include "sylva/core/plantlod/PlantLodBuilder.h"
#include "sylva/core/plantlod/PlodFile.h"
#include "sylva/core/plantlod/PrimitiveRasterizer.h"
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

// GPU bytes of what a renderer draws at an ellipsoid level: the level's ellipsoids and
// the lines drawn at its error, in the .plod element sizes (uploaded as they are).
std::uint64_t levelBytes(const PlantLodLevel& level) {
    return std::uint64_t{level.ellipsoidCount} * 112u + std::uint64_t{level.lineCount} * 64u;
}

// The equal-memory budget of seed 001 Fig. 3.19: 19 kB (19 × 1024 bytes).
constexpr std::uint64_t kComparisonBytes = 19u * 1024u;

// Luminance [0, 1] → grey sRGB-ish byte (square root: dark foliage stays visible).
std::uint8_t greyByte(float value) {
    return static_cast<std::uint8_t>(
        std::lround(255.0f * std::sqrt(std::clamp(value, 0.0f, 1.0f))));
}

// One montage row: the source mesh, every ellipsoid/line level, every billboard level,
// each seen from the builder's first view (PrimitiveRasterizer, luminance as grey) —
// exactly the images the error metric compares.
std::vector<std::vector<float>> montageRow(const PlantModel& model, const PlantLod& lod, int size,
                                           int& cells) {
    const PrimitiveRasterizer rasterizer(lod.boundsMinimum, lod.boundsMaximum, size, 8, 2);
    std::vector<std::vector<float>> images;
    RasterFrame frame = rasterizer.blankFrame();
    rasterizer.drawMesh(model, PlantPart::Leaf, true, 0, frame);
    images.push_back(rasterizer.resolve(frame));
    for (std::size_t k = 0; k < lod.levels.size(); ++k) {
        std::vector<LodEllipsoid> ellipsoids;
        for (const LodEllipsoid& e : lod.ellipsoids) {
            if (e.level == k) {
                ellipsoids.push_back(e);
            }
        }
        std::vector<LodLine> lines;
        const float error = lod.levels[k].errorMinimum;
        for (const LodLine& l : lod.lines) {
            if (l.errorMinimum <= error && error < l.errorMaximum) {
                lines.push_back(l);
            }
        }
        rasterizer.clearFrame(frame);
        rasterizer.drawEllipsoids(ellipsoids, 0, frame);
        rasterizer.drawLines(lines, 0, frame);
        images.push_back(rasterizer.resolve(frame));
    }
    for (const BillboardLevel& level : lod.billboards.levels) {
        rasterizer.clearFrame(frame);
        rasterizer.drawMesh(BillboardCloudBuilder::levelModel(level, model.name), PlantPart::Leaf,
                            true, 0, frame);
        images.push_back(rasterizer.resolve(frame));
    }
    cells = std::max(cells, static_cast<int>(images.size()));
    return images;
}

Status writeMontage(const std::string& path,
                    const std::vector<std::vector<std::vector<float>>>& rows, int size, int cells) {
    const int width = size * cells, height = size * static_cast<int>(rows.size());
    std::vector<std::uint8_t> rgba(static_cast<std::size_t>(width) * height * 4, 255);
    for (std::size_t r = 0; r < rows.size(); ++r) {
        for (std::size_t c = 0; c < rows[r].size(); ++c) {
            for (int y = 0; y < size; ++y) {
                for (int x = 0; x < size; ++x) {
                    // Background (0) white, the plant dark on it; a grey border per cell.
                    const float v = rows[r][c][static_cast<std::size_t>(y) * size + x];
                    const bool border = x == 0 || y == 0;
                    const std::uint8_t g = border ? 160 : v > 0.0f ? greyByte(v) : 255;
                    const std::size_t at =
                        (static_cast<std::size_t>(r * size + y) * width + c * size + x) * 4;
                    rgba[at] = rgba[at + 1] = rgba[at + 2] = g;
                }
            }
        }
    }
    return ImageWriter::writeRgba8(path, width, height, rgba);
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
    const bool billboards = !command.has("no-billboards");
    const std::optional<std::string> montagePath = command.get("montage");
    constexpr int kMontageSize = 160;
    std::vector<std::vector<std::vector<float>>> montageRows;
    int montageCells = 0;
    // Equal memory: the lowest error of any LoD level / billboard level of any model
    // within the budget.
    double rmseLodBudget = std::numeric_limits<double>::infinity();
    double rmseBillboardBudget = std::numeric_limits<double>::infinity();
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
            metrics.emplace_back("bytes" + suffix, static_cast<double>(levelBytes(lod->levels[k])));
            if (levelBytes(lod->levels[k]) <= kComparisonBytes) {
                rmseLodBudget = std::min(rmseLodBudget, double(lod->levels[k].imageError));
            }
        }
        if (billboards) {
            // Billboard clouds at the default texel density (reported per level) and at
            // coarser densities, whose smaller atlases reach the equal-memory budget.
            for (const int texels : {256, 128, 64, 32, 16}) {
                BillboardCloudOptions cloudOptions;
                cloudOptions.texelsAcrossModel = texels;
                PlantLod withClouds;
                withClouds.boundsMinimum = lod->boundsMinimum;
                withClouds.boundsMaximum = lod->boundsMaximum;
                if (Status built = addBillboardClouds(model, withClouds, options, cloudOptions);
                    !built) {
                    reportError(built.error().message);
                    return 1;
                }
                for (std::size_t k = 0; k < withClouds.billboards.levels.size(); ++k) {
                    const BillboardLevel& level = withClouds.billboards.levels[k];
                    if (texels == 256) {
                        const std::string suffix = "_l" + std::to_string(k) + "_" + m.label;
                        metrics.emplace_back("bbc_planes" + suffix, level.quads.size());
                        metrics.emplace_back("bbc_rmse" + suffix, level.imageError);
                        metrics.emplace_back("bbc_bytes" + suffix,
                                             static_cast<double>(level.byteSize()));
                    }
                    if (level.byteSize() <= kComparisonBytes) {
                        rmseBillboardBudget =
                            std::min(rmseBillboardBudget, double(level.imageError));
                    }
                }
                if (texels == 256) {
                    lod->billboards = withClouds.billboards;
                }
            }
        }
        if (montagePath) {
            montageRows.push_back(montageRow(model, *lod, kMontageSize, montageCells));
        }
        if (!command.has("json")) {
            std::fprintf(stderr, "plantlod: %s leaves in %.1f s\n", m.label, seconds);
        }
    }
    metrics.emplace_back("speedup_vs_thesis_min", speedup);
    if (billboards) {
        metrics.emplace_back("rmse_lod_19kb", rmseLodBudget);
        metrics.emplace_back("rmse_bbc_19kb", rmseBillboardBudget);
    }
    if (montagePath) {
        // Every other preset at 1,000 leaves, for a look at each kind of plant.
        for (const std::string& preset : PlantGenerator::presetNames()) {
            if (preset == "oak") {
                continue;
            }
            PlantGeneratorOptions generatorOptions;
            generatorOptions.seed = 7;
            generatorOptions.leafCount = 1000;
            Result<PlantModel> model =
                PlantGenerator::generate(PlantGenerator::preset(preset).value(), generatorOptions);
            if (!model) {
                reportError(model.error().message);
                return 1;
            }
            Result<PlantLod> lod = buildPlantLod(*model, options);
            if (!lod) {
                reportError(lod.error().message);
                return 1;
            }
            if (billboards) {
                if (Status built = addBillboardClouds(*model, *lod, options); !built) {
                    reportError(built.error().message);
                    return 1;
                }
            }
            montageRows.push_back(montageRow(*model, *lod, kMontageSize, montageCells));
        }
        if (Status written = writeMontage(*montagePath, montageRows, kMontageSize, montageCells);
            !written) {
            reportError(written.error().message);
            return 1;
        }
    }
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
