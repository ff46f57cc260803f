// `sylva analyse PROJECT [--only NAME] [--out DIR] [--json] [-D name=value]
// [--set block.attr=value]`: evaluates the project's analysis blocks (ztv) and writes
// their GeoTIFFs and styled PNG maps (core/analysis; the map is the GeoTIFF's path with
// the extension .png). Every selected block is planned against its DEM first,
// so a located error in any of them stops the command before a file is written; each
// file is written atomically, and a study whose GeoTIFF fails leaves no map either. Progress goes
// to stderr; --json prints one summary per block on stdout (name, output, cells, visible cells and
// share, targets, seconds).
#include <chrono>
#include <cstdio>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "CommandLine.h"
#include "Commands.h"
#include "ProjectSession.h"
#include "sylva/core/analysis/ScreeningSurface.h"
#include "sylva/core/analysis/Viewshed.h"
#include "sylva/core/analysis/ZtvMap.h"
#include "sylva/core/analysis/ZtvStudy.h"
#include "sylva/core/analysis/ZtvWriter.h"
#include "sylva/dsl/ProjectLoader.h"

namespace sylva::app {

namespace {

constexpr const char* kUsage =
    "usage: sylva analyse PROJECT [--only NAME] [--out DIR] [--json] [-D name=value] "
    "[--set block.attr=value]";

// The ztv blocks to run: all, or the one --only names (nullopt after reporting).
std::optional<std::vector<const Block*>> selectBlocks(const ProjectModel& model,
                                                      const std::optional<std::string>& only) {
    std::vector<const Block*> blocks;
    for (const Block& block : model.ztvs)
        if (!only || block.name == *only)
            blocks.push_back(&block);
    if (only && blocks.empty()) {
        std::string names;
        for (const Block& block : model.ztvs)
            names += (names.empty() ? "" : ", ") + block.name;
        reportError("--only " + *only + ": the project has no ztv block of that name" +
                    (names.empty() ? std::string(" (it has none)") : " (it has: " + names + ")"));
        return std::nullopt;
    }
    if (blocks.empty())
        reportError(model.file.string() + ": the project has no ztv block");
    return blocks.empty() ? std::nullopt : std::optional(blocks);
}

// Computes and writes one study; the summary for --json, or nullopt after reporting.
std::optional<nlohmann::ordered_json> runStudy(const ZtvStudy& study,
                                               const std::filesystem::path& outFolder) {
    const auto start = std::chrono::steady_clock::now();
    auto grid = readElevationGrid(study.demPath, study.grid);
    if (!grid) {
        reportError("ztv '" + study.name + "': " + grid.error().message);
        return std::nullopt;
    }
    std::fprintf(stderr, "ztv '%s': %d x %d cells of %.1f m, %zu target(s)\n", study.name.c_str(),
                 study.grid.width, study.grid.height, study.grid.cellWidth, study.targets.size());
    std::optional<ScreeningSurface> screened;
    if (!study.screens.empty()) {
        auto surface = buildScreeningSurface(*grid, study.screens);
        if (!surface) {
            reportError("ztv '" + study.name + "': " + surface.error().message);
            return std::nullopt;
        }
        screened = std::move(*surface);
        std::fprintf(stderr, "ztv '%s': screened by %zu building and %zu canopy cells\n",
                     study.name.c_str(), screened->buildingCells, screened->canopyCells);
    }
    auto result = screened ? computeViewshed(*grid, screened->surface, study.targets, study.options)
                           : computeViewshed(*grid, study.targets, study.options);
    if (!result) {
        reportError("ztv '" + study.name + "': " + result.error().message);
        return std::nullopt;
    }
    const std::filesystem::path path = outFolder / study.output;
    std::error_code error;
    std::filesystem::create_directories(path.parent_path(), error);
    std::filesystem::path mapPath = path;
    mapPath.replace_extension(".png");
    const ZtvMap map = drawZtvMap(*grid, *result, study.targets, {study.name, study.options});
    if (Status written = writeZtvMap(mapPath, map); !written) {
        reportError("ztv '" + study.name + "': " + written.error().message);
        return std::nullopt;
    }
    if (Status written = writeZtvGeoTiff(path, *result, study.crsWkt); !written) {
        std::filesystem::remove(mapPath, error);  // no map without its GeoTIFF
        reportError("ztv '" + study.name + "': " + written.error().message);
        return std::nullopt;
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const std::size_t visible = result->visibleCells();
    const double share = double(visible) / double(result->cells());
    std::fprintf(stderr, "ztv '%s': %.1f %% of cells see a target; wrote %s and %s (%.2f s)\n",
                 study.name.c_str(), 100.0 * share, path.string().c_str(), mapPath.string().c_str(),
                 seconds);
    nlohmann::ordered_json summary;
    summary["name"] = study.name;
    summary["output"] = path.string();
    summary["map"] = mapPath.string();
    summary["cells"] = result->cells();
    summary["visible_cells"] = visible;
    summary["visible_share"] = share;
    summary["targets"] = study.targets.size();
    summary["screened"] = screened.has_value();
    summary["building_cells"] = screened ? screened->buildingCells : 0;
    summary["canopy_cells"] = screened ? screened->canopyCells : 0;
    summary["seconds"] = seconds;
    return summary;
}

}  // namespace

int runAnalyse(const std::vector<std::string>& originalArguments) {
    std::vector<std::string> arguments = originalArguments;
    std::string setError;
    auto sets = extractSets(arguments, setError);
    const ParsedCommandLine command = parseCommandLine(
        arguments, {{"help", false}, {"json", false}, {"only", true}, {"out", true}});
    if (command.has("help")) {
        std::puts(kUsage);
        return 0;
    }
    std::string error = !setError.empty() ? setError : command.error;
    if (error.empty() && command.positional.size() != 1)
        error = "analyse needs exactly one project file";
    if (!error.empty()) {
        reportError(error + "\n" + kUsage);
        return 2;
    }
    dsl::LoadResult loaded = dsl::loadProject(command.positional[0], loadOptionsFor(command, sets));
    printDiagnostics(loaded);
    if (loaded.hasErrors() || !loaded.model)
        return 1;
    const auto blocks = selectBlocks(*loaded.model, command.get("only"));
    if (!blocks)
        return 1;
    std::vector<ZtvStudy> studies;
    bool failed = false;
    for (const Block* block : *blocks) {
        auto study = planZtv(*loaded.model, *block);
        if (study) {
            studies.push_back(std::move(*study));
        } else {
            std::fprintf(stderr, "error: %s\n", study.error().message.c_str());
            failed = true;
        }
    }
    if (failed)
        return 1;
    const std::filesystem::path outFolder = command.get("out").value_or(".");
    nlohmann::ordered_json summaries = nlohmann::ordered_json::array();
    for (const ZtvStudy& study : studies) {
        auto summary = runStudy(study, outFolder);
        if (!summary)
            return 1;
        summaries.push_back(std::move(*summary));
    }
    if (command.has("json"))
        std::fputs((summaries.dump(2) + "\n").c_str(), stdout);
    return 0;
}

}  // namespace sylva::app
