// `sylva plant generate --preset NAME --seed N [--leaves N] -o MODEL.gltf|.glb`: a
// procedural tree (PlantGenerator) written as glTF, atomically.
// `sylva plant montage [--seed N] [--leaves N] [--size WxH] [--billboards] -o IMAGE.png`:
// every preset side by side, rendered by the software rasterizer (for the eye); with
// --billboards their finest billboard-cloud level instead.
// `sylva plant info MODEL`: imports a model and prints what the importer made of it.
#include <charconv>
#include <cstdio>

#include "CommandLine.h"
#include "Commands.h"
#include "ProjectSession.h"
#include "sylva/core/image/ImageWriter.h"
#include "sylva/core/plantlod/BillboardCloudBuilder.h"
#include "sylva/core/plantlod/PlantGenerator.h"
#include "sylva/core/plantlod/PlantGltfWriter.h"
#include "sylva/core/plantlod/PlantImporter.h"
#include "sylva/core/plantlod/PlantRasterizer.h"

namespace sylva::app {

namespace {

const char* kUsage =
    "usage: sylva plant generate --preset NAME --seed N [--leaves N] -o MODEL.gltf|MODEL.glb\n"
    "       sylva plant montage [--seed N] [--leaves N] [--size WxH] [--billboards] -o IMAGE.png\n"
    "       sylva plant info MODEL.gltf|.glb|.obj\n";

template <typename Integer>
bool parseInteger(const std::string& text, Integer& value) {
    auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
    return error == std::errc() && end == text.data() + text.size();
}

// Shared option checks of generate and montage; empty string when fine.
std::string readGeneratorOptions(const ParsedCommandLine& command, PlantGeneratorOptions& options) {
    if (auto seed = command.get("seed")) {
        if (!parseInteger(*seed, options.seed)) {
            return "--seed needs a non-negative integer, got '" + *seed + "'";
        }
    }
    if (auto leaves = command.get("leaves")) {
        int count = 0;
        if (!parseInteger(*leaves, count) || count < 0 || count > 2000000) {
            return "--leaves needs an integer in [0, 2000000], got '" + *leaves + "'";
        }
        options.leafCount = count;
    }
    return "";
}

int usageError(const std::string& message) {
    reportError(message);
    std::fputs(kUsage, stderr);
    return 2;
}

int runGenerate(const ParsedCommandLine& command) {
    PlantGeneratorOptions options;
    std::string error = readGeneratorOptions(command, options);
    if (error.empty() && !command.positional.empty()) {
        error = "unexpected argument '" + command.positional.front() + "'";
    }
    if (error.empty() && !command.has("preset")) {
        error = "plant generate needs --preset NAME";
    }
    if (error.empty() && !command.has("seed")) {
        error = "plant generate needs --seed N";
    }
    if (error.empty() && !command.has("out")) {
        error = "plant generate needs -o MODEL.gltf or MODEL.glb";
    }
    std::filesystem::path out = command.get("out").value_or("");
    if (error.empty() && out.extension() != ".gltf" && out.extension() != ".glb") {
        error = "-o must name a .gltf or .glb file, got '" + out.string() + "'";
    }
    if (!error.empty()) {
        return usageError(error);
    }
    Result<TreeParameters> preset = PlantGenerator::preset(*command.get("preset"));
    if (!preset) {
        return usageError(preset.error().message);
    }
    Result<PlantModel> model = PlantGenerator::generate(*preset, options);
    if (!model) {
        reportError(model.error().message);
        return 1;
    }
    if (Status written = PlantGltfWriter::write(*model, out); !written) {
        reportError(written.error().message);
        return 1;
    }
    std::printf("%s: %s, seed %llu, %zu leaf and %zu branch triangles, %zu skeleton segments\n",
                out.string().c_str(), preset->name.c_str(),
                static_cast<unsigned long long>(options.seed),
                model->triangleCount(PlantPart::Leaf), model->triangleCount(PlantPart::Branch),
                model->skeleton.size());
    return 0;
}

int runMontage(const ParsedCommandLine& command) {
    PlantGeneratorOptions options;
    std::string error = readGeneratorOptions(command, options);
    int width = 320;
    int height = 400;
    if (auto size = command.get("size"); error.empty() && size) {
        const std::size_t x = size->find('x');
        if (x == std::string::npos || !parseInteger(size->substr(0, x), width) ||
            !parseInteger(size->substr(x + 1), height) || width < 16 || height < 16 ||
            width > 4096 || height > 4096) {
            error = "--size needs WxH with 16 <= W, H <= 4096, got '" + *size + "'";
        }
    }
    if (error.empty() && !command.has("out")) {
        error = "plant montage needs -o IMAGE.png";
    }
    if (!error.empty()) {
        return usageError(error);
    }
    const std::vector<std::string> names = PlantGenerator::presetNames();
    RasterImage montage;
    montage.width = width * int(names.size());
    montage.height = height;
    montage.rgba.assign(std::size_t(montage.width) * std::size_t(height) * 4, 0);
    for (std::size_t i = 0; i < names.size(); ++i) {
        Result<PlantModel> model =
            PlantGenerator::generate(PlantGenerator::preset(names[i]).value(), options);
        if (!model) {
            reportError(model.error().message);
            return 1;
        }
        if (command.has("billboards")) {
            // Each tree as its finest billboard-cloud level, for comparison.
            Result<BillboardCloud> cloud = BillboardCloudBuilder::build(*model);
            if (!cloud) {
                reportError(cloud.error().message);
                return 1;
            }
            model = BillboardCloudBuilder::levelModel(cloud->levels.front(), model->name);
        }
        const RasterImage tile = PlantRasterizer::renderSide(*model, width, height);
        for (int y = 0; y < height; ++y) {
            for (int x = 0; x < width; ++x) {
                const std::uint8_t* source =
                    &tile.rgba[(std::size_t(y) * std::size_t(width) + std::size_t(x)) * 4];
                std::uint8_t* target = &montage.rgba[(std::size_t(y) * std::size_t(montage.width) +
                                                      i * std::size_t(width) + std::size_t(x)) *
                                                     4];
                // Sky-grey backdrop where nothing was drawn.
                const bool drawn = source[3] != 0;
                target[0] = drawn ? source[0] : 200;
                target[1] = drawn ? source[1] : 215;
                target[2] = drawn ? source[2] : 230;
                target[3] = 255;
            }
        }
    }
    const std::filesystem::path out = *command.get("out");
    if (Status written = ImageWriter::writeRgba8(out, montage.width, montage.height, montage.rgba);
        !written) {
        reportError(written.error().message);
        return 1;
    }
    std::printf("%s: %zu presets\n", out.string().c_str(), names.size());
    return 0;
}

int runInfo(const ParsedCommandLine& command) {
    if (command.positional.size() != 1) {
        return usageError("plant info needs exactly one model file");
    }
    Result<PlantModel> model = PlantImporter::import(command.positional.front());
    if (!model) {
        reportError(model.error().message);
        return 1;
    }
    const glm::vec3 minimum = model->boundsMinimum();
    const glm::vec3 maximum = model->boundsMaximum();
    std::printf(
        "%s: %zu materials, %zu meshes, %zu leaf and %zu branch triangles, %zu skeleton segments, "
        "size %.2f x %.2f x %.2f m\n",
        command.positional.front().c_str(), model->materials.size(), model->meshes.size(),
        model->triangleCount(PlantPart::Leaf), model->triangleCount(PlantPart::Branch),
        model->skeleton.size(), double(maximum.x - minimum.x), double(maximum.y - minimum.y),
        double(maximum.z - minimum.z));
    return 0;
}

}  // namespace

int runPlant(const std::vector<std::string>& originalArguments) {
    if (originalArguments.empty() || originalArguments.front() == "--help") {
        std::fputs(kUsage, originalArguments.empty() ? stderr : stdout);
        return originalArguments.empty() ? 2 : 0;
    }
    const std::string action = originalArguments.front();
    // `-o FILE` is spelled the short way; CommandLine knows only long options.
    std::vector<std::string> arguments;
    for (std::size_t i = 1; i < originalArguments.size(); ++i) {
        arguments.push_back(originalArguments[i] == "-o" ? "--out" : originalArguments[i]);
    }
    std::vector<OptionSpec> specs = {{"help", false}};
    if (action == "generate") {
        specs.insert(specs.end(), {{"preset"}, {"seed"}, {"leaves"}, {"out"}});
    } else if (action == "montage") {
        specs.insert(specs.end(), {{"seed"}, {"leaves"}, {"size"}, {"out"}, {"billboards", false}});
    } else if (action != "info") {
        return usageError("unknown plant action '" + action + "' (generate, montage, info)");
    }
    const ParsedCommandLine command = parseCommandLine(arguments, specs);
    if (command.has("help")) {
        std::fputs(kUsage, stdout);
        return 0;
    }
    if (!command.error.empty()) {
        return usageError(command.error);
    }
    if (action == "generate") {
        return runGenerate(command);
    }
    if (action == "montage") {
        return runMontage(command);
    }
    return runInfo(command);
}

}  // namespace sylva::app
