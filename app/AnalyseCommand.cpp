// `sylva analyse PROJECT [--only NAME] [--out DIR] [--json] [--force] [--resume] [--shard i/N]
// [-D name=value] [--set block.attr=value]`: evaluates the project's analysis blocks (ztv,
// shadow_study) and writes their GeoTIFFs and PNG maps (core/analysis; a ztv's map is the GeoTIFF's
// path with the extension .png; a shadow study writes a folder per block). --force lifts
// the grid's cell limit (ZtvStudy::kMaxCells, ShadowStudy::kMaxCells). Every selected block is
// planned against its DEM first, so a located error in any of them stops the command before a file
// is written; each file is written atomically, and a study whose GeoTIFF fails leaves no map
// either. Progress goes to stderr; --json prints one summary per block on stdout (name, output,
// cells, visible cells and share, targets, seconds). Like `render`, every finished block is
// recorded in a manifest (DIR/analyse-manifest.json: output, kind, the block's
// analysisHash, seconds); --resume skips a block whose record has the current hash and
// whose output exists; --shard i/N runs every N-th block from the i-th (all are planned,
// so errors anywhere still stop every shard). Exit 75 when the manifest cannot be saved.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "CommandLine.h"
#include "Commands.h"
#include "ProjectSession.h"
#include "sylva/core/analysis/AnalysisHash.h"
#include "sylva/core/analysis/GridGeoTiff.h"
#include "sylva/core/analysis/ScreeningSurface.h"
#include "sylva/core/analysis/ShadowMap.h"
#include "sylva/core/analysis/ShadowStudy.h"
#include "sylva/core/analysis/Viewshed.h"
#include "sylva/core/analysis/ZtvMap.h"
#include "sylva/core/analysis/ZtvStudy.h"
#include "sylva/core/analysis/ZtvWriter.h"
#include "sylva/core/scene/RenderManifest.h"
#include "sylva/core/scene/ViewSeries.h"
#include "sylva/dsl/ProjectLoader.h"

namespace sylva::app {

namespace {

constexpr const char* kUsage =
    "usage: sylva analyse PROJECT [--only NAME] [--out DIR] [--json] [--force] [--resume] "
    "[--shard i/N] [-D name=value] [--set block.attr=value]";

// The analysis blocks (ztv, shadow_study) to run: all, or the one --only names
// (nullopt after reporting).
std::optional<std::vector<const Block*>> selectBlocks(const ProjectModel& model,
                                                      const std::optional<std::string>& only) {
    std::vector<const Block*> blocks;
    std::string names;
    for (const std::vector<Block>* kind : {&model.ztvs, &model.shadowStudies})
        for (const Block& block : *kind) {
            if (!only || block.name == *only)
                blocks.push_back(&block);
            names += (names.empty() ? "" : ", ") + block.name;
        }
    if (only && blocks.empty()) {
        reportError("--only " + *only + ": the project has no ztv block of that name" +
                    (names.empty() ? std::string(" (it has none)") : " (it has: " + names + ")"));
        return std::nullopt;
    }
    if (blocks.empty())
        reportError(model.file.string() + ": the project has no ztv block");
    return blocks.empty() ? std::nullopt : std::optional(blocks);
}

// The screens of a study as heights above the ground per cell (empty: none).
std::optional<std::vector<float>> screenHeights(const std::string& what, const ElevationGrid& grid,
                                                const std::vector<ScreenLayer>& screens) {
    if (screens.empty())
        return std::vector<float>();
    auto surface = buildScreeningSurface(grid, screens);
    if (!surface) {
        reportError(what + ": " + surface.error().message);
        return std::nullopt;
    }
    std::vector<float> heights(grid.heights.size());
    for (std::size_t i = 0; i < heights.size(); ++i)
        heights[i] =
            std::isnan(grid.heights[i]) ? 0.0f : surface->surface.heights[i] - grid.heights[i];
    return heights;
}

// The window's cells of a row-major grid `width` cells wide (empty stays empty).
std::vector<float> croppedCells(const std::vector<float>& cells, int width,
                                const CellWindow& window) {
    std::vector<float> out;
    if (cells.empty())
        return out;
    out.reserve(std::size_t(window.width) * std::size_t(window.height));
    for (int row = window.row; row < window.row + window.height; ++row) {
        const auto first = cells.begin() + std::ptrdiff_t(row) * width + window.col;
        out.insert(out.end(), first, first + window.width);
    }
    return out;
}

// The window of an elevation grid as a grid of its own.
ElevationGrid croppedGrid(const ElevationGrid& grid, const CellWindow& window) {
    ElevationGrid out;
    out.crsWkt = grid.crsWkt;
    out.geometry = grid.geometry;
    out.geometry.originX += window.col * grid.geometry.cellWidth;
    out.geometry.originY -= window.row * grid.geometry.cellHeight;
    out.geometry.width = window.width;
    out.geometry.height = window.height;
    out.heights = croppedCells(grid.heights, grid.geometry.width, window);
    return out;
}

// Writes one date of a shadow study: the sun-hours GeoTIFF, a PNG per frame with the sun
// up and the contact sheet; the paths written go to `written`. False after reporting.
bool writeShadowDay(const ShadowStudy& study, const ElevationGrid& grid,
                    const std::vector<float>& screens, const ShadowDay& day,
                    const std::filesystem::path& folder,
                    std::vector<std::filesystem::path>& written) {
    const std::string what = "shadow_study '" + study.name + "'";
    const std::filesystem::path tif = folder / ("sun_hours_" + day.date + ".tif");
    const GridBand band{"sun_hours", &day.sunHours};
    if (Status ok = writeGridGeoTiff(tif, study.grid, std::span(&band, 1), study.crsWkt); !ok) {
        reportError(what + ": " + ok.error().message);
        return false;
    }
    written.push_back(tif);
    std::vector<RgbaImage> frames;
    std::vector<std::string> captions;
    const int scale = shadowFrameScale(study.grid);
    for (const ShadowFrame& frame : day.frames) {
        if (!(frame.elevation > 0.0))
            continue;
        RgbaImage image = drawShadowFrame(grid, screens, study.site, frame, day.date, scale);
        std::string stamp = frame.label;
        stamp.erase(std::remove(stamp.begin(), stamp.end(), ':'), stamp.end());
        const std::filesystem::path png = folder / ("shadow_" + day.date + "_" + stamp + ".png");
        if (Status ok = writeShadowImage(png, image); !ok) {
            reportError(what + ": " + ok.error().message);
            return false;
        }
        written.push_back(png);
        frames.push_back(std::move(image));
        captions.push_back(frame.label);
    }
    const std::filesystem::path sheet = folder / ("contact_" + day.date + ".png");
    if (Status ok = writeShadowImage(sheet, drawContactSheet(frames, captions, 4, 240)); !ok) {
        reportError(what + ": " + ok.error().message);
        return false;
    }
    written.push_back(sheet);
    return true;
}

// Computes and writes one shadow study; the summary for --json, or nullopt after
// reporting (and removing what it had written).
std::optional<nlohmann::ordered_json> runShadowStudy(const ShadowStudy& study,
                                                     const std::filesystem::path& outFolder) {
    const auto start = std::chrono::steady_clock::now();
    const std::string what = "shadow_study '" + study.name + "'";
    const bool grown = study.casterGrid.width > 0;
    auto ground = readElevationGrid(study.demPath, grown ? study.casterGrid : study.grid);
    if (!ground) {
        reportError(what + ": " + ground.error().message);
        return std::nullopt;
    }
    auto casterScreens = screenHeights(what, *ground, study.screens);
    if (!casterScreens)
        return std::nullopt;
    const ShadowCaster caster(*ground, *casterScreens, grown ? study.casterWindow : CellWindow{});
    // The study's own grid and screens, for the maps.
    const ElevationGrid grid = croppedGrid(*ground, caster.window());
    const std::vector<float> screens =
        croppedCells(*casterScreens, ground->geometry.width, caster.window());
    const std::filesystem::path folder = outFolder / study.output;
    std::error_code error;
    std::filesystem::create_directories(folder, error);
    std::vector<std::filesystem::path> written;
    nlohmann::ordered_json dates = nlohmann::ordered_json::array();
    for (const std::string& date : study.dates) {
        std::fprintf(stderr, "%s: %s, %d x %d cells of %.1f m\n", what.c_str(), date.c_str(),
                     study.grid.width, study.grid.height, study.grid.cellWidth);
        auto day = computeShadowDay(caster, study, date);
        if (!day || !writeShadowDay(study, grid, screens, *day, folder, written)) {
            if (!day)
                reportError(what + ": " + day.error().message);
            for (const std::filesystem::path& path : written)
                std::filesystem::remove(path, error);  // nothing half-written
            return std::nullopt;
        }
        double sum = 0.0;
        std::size_t valid = 0;
        for (float h : day->sunHours)
            if (!std::isnan(h)) {
                sum += h;
                ++valid;
            }
        nlohmann::ordered_json entry = {{"date", date},
                                        {"frames", day->frames.size()},
                                        {"mean_sun_hours", valid > 0 ? sum / double(valid) : 0.0}};
        if (!study.site.empty()) {
            entry["site_mean_sun_hours"] = day->siteMeanSunHours;
            entry["site_share_at_target"] = day->siteShareAtTarget;
            std::fprintf(stderr,
                         "%s: %s: the site (%zu cells) gets %.2f h of sun on average; "
                         "%.1f %% of it gets at least %.1f h\n",
                         what.c_str(), date.c_str(), study.siteCells, day->siteMeanSunHours,
                         100.0 * day->siteShareAtTarget, study.sunHoursTarget);
        }
        dates.push_back(std::move(entry));
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::fprintf(stderr, "%s: wrote %zu files to %s (%.2f s)\n", what.c_str(), written.size(),
                 folder.string().c_str(), seconds);
    nlohmann::ordered_json summary;
    summary["name"] = study.name;
    summary["kind"] = "shadow_study";
    summary["output"] = folder.string();
    summary["cells"] = std::size_t(study.grid.width) * std::size_t(study.grid.height);
    if (!study.site.empty()) {
        summary["site_cells"] = study.siteCells;
        summary["sun_hours_target"] = study.sunHoursTarget;
    }
    summary["dates"] = std::move(dates);
    summary["files"] = written.size();
    summary["seconds"] = seconds;
    return summary;
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
    const std::size_t firstProposal = study.targets.size() - study.proposal.size();
    for (std::size_t i = 0; i < study.proposal.size(); ++i)
        std::fprintf(stderr, "ztv '%s': target %zu: %s, top %.1f m above its base\n",
                     study.name.c_str(), firstProposal + i + 1, study.proposal[i].label.c_str(),
                     study.targets[firstProposal + i].height);
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
    summary["kind"] = "ztv";
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

namespace {

// One selected block, planned: its study, what decides its files and where they go.
struct PlannedBlock {
    const Block* block = nullptr;
    std::optional<ZtvStudy> ztv;
    std::optional<ShadowStudy> shadow;
    std::uint64_t hash = 0;  // analysisHash
    std::string output;      // the GeoTIFF (ztv) or folder (shadow_study), relative to --out
};

// Plans every block (all of them, so any located error stops the run before a file is
// written); nullopt after reporting.
std::optional<std::vector<PlannedBlock>> planBlocks(const ProjectModel& model,
                                                    const std::vector<const Block*>& blocks,
                                                    bool force) {
    std::vector<PlannedBlock> planned;
    bool failed = false;
    for (const Block* block : blocks) {
        PlannedBlock item;
        item.block = block;
        item.hash = analysisHash(model, *block);
        Status ok = Status::success();
        if (block->keyword == "shadow_study") {
            auto study = planShadowStudy(model, *block, force);
            ok = study ? Status::success() : Status(study.error());
            if (study) {
                item.output = study->output;
                item.shadow = std::move(*study);
            }
        } else {
            auto study = planZtv(model, *block, force);
            ok = study ? Status::success() : Status(study.error());
            if (study) {
                item.output = study->output;
                item.ztv = std::move(*study);
            }
        }
        if (!ok) {
            std::fprintf(stderr, "error: %s\n", ok.error().message.c_str());
            failed = true;
        }
        planned.push_back(std::move(item));
    }
    return failed ? std::nullopt : std::optional(std::move(planned));
}

// Whether --resume may skip `item`: the manifest has its output with the same hash and
// the output (GeoTIFF, or the study's folder) is there.
bool upToDate(const RenderManifest& manifest, const PlannedBlock& item,
              const std::filesystem::path& outFolder) {
    const auto found = manifest.entries().find(item.output);
    std::error_code error;
    return found != manifest.entries().end() && found->second.hash == item.hash &&
           std::filesystem::exists(outFolder / item.output, error);
}

// Runs the planned blocks of this shard (--shard i/N: every N-th from the i-th), skipping
// up-to-date ones with --resume and recording each finished block in the manifest.
int runPlanned(const std::vector<PlannedBlock>& planned, const ParsedCommandLine& command,
               std::pair<int, int> shard) {
    const std::filesystem::path outFolder = command.get("out").value_or(".");
    RenderManifest manifest(outFolder / "analyse-manifest.json");
    if (Status loaded = manifest.load(); !loaded) {
        reportError(loaded.error().message);
        return 1;
    }
    nlohmann::ordered_json summaries = nlohmann::ordered_json::array();
    for (std::size_t i = 0; i < planned.size(); ++i) {
        const PlannedBlock& item = planned[i];
        if (int(i % std::size_t(shard.second)) != shard.first - 1)
            continue;
        const std::string what = item.block->keyword + " '" + item.block->name + "'";
        if (command.has("resume") && upToDate(manifest, item, outFolder)) {
            std::fprintf(stderr, "%s: up to date, skipped (--resume)\n", what.c_str());
            summaries.push_back({{"name", item.block->name},
                                 {"kind", item.block->keyword},
                                 {"output", (outFolder / item.output).string()},
                                 {"skipped", true}});
            continue;
        }
        auto summary =
            item.ztv ? runStudy(*item.ztv, outFolder) : runShadowStudy(*item.shadow, outFolder);
        if (!summary)
            return 1;
        ManifestEntry entry;
        entry.output = item.output;
        entry.kind = item.block->keyword;
        entry.view = item.block->name;
        entry.hash = item.hash;
        entry.seconds = (*summary)["seconds"].get<double>();
        manifest.record(entry);
        if (Status saved = manifest.save(); !saved) {
            reportError(what + ": written, but " + saved.error().message +
                        "; run again (--resume cannot skip it)");
            return 75;
        }
        summaries.push_back(std::move(*summary));
    }
    if (command.has("json"))
        std::fputs((summaries.dump(2) + "\n").c_str(), stdout);
    return 0;
}

}  // namespace

int runAnalyse(const std::vector<std::string>& originalArguments) {
    std::vector<std::string> arguments = originalArguments;
    std::string setError;
    auto sets = extractSets(arguments, setError);
    const ParsedCommandLine command = parseCommandLine(arguments, {{"help", false},
                                                                   {"json", false},
                                                                   {"force", false},
                                                                   {"resume", false},
                                                                   {"only", true},
                                                                   {"shard", true},
                                                                   {"out", true}});
    if (command.has("help")) {
        std::puts(kUsage);
        return 0;
    }
    std::string error = !setError.empty() ? setError : command.error;
    if (error.empty() && command.positional.size() != 1)
        error = "analyse needs exactly one project file";
    std::pair<int, int> shard{1, 1};
    if (std::optional<std::string> text = command.get("shard"); text && error.empty()) {
        auto parsed = ViewSeries::parseShard(*text);
        if (parsed)
            shard = *parsed;
        else
            error = "--shard " + *text + ": " + parsed.error().message;
    }
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
    const auto planned = planBlocks(*loaded.model, *blocks, command.has("force"));
    if (!planned)
        return 1;
    return runPlanned(*planned, command, shard);
}

}  // namespace sylva::app
