// `sylva montage PROJECT [--only NAME] [--out DIR] [--json] [-D name=value]
// [--set block.attr=value]`: the project's `photo` blocks as photomontages (issue 18; LI
// TGN 06/19 Types 2–4; render::PhotomontageRenderer). Every selected block is read and its
// photograph loaded first, so a located error in any of them stops the command before
// anything renders. Per block it writes PREFIX_montage.png, PREFIX_wireline.png,
// PREFIX_model.png and PREFIX.json (camera, match residuals, proposal pixels; with `sheet`
// also PREFIX.sheet.pdf/.png, PREFIX_map.png and the viewpoint record in the JSON), each
// atomically; when one write fails, the block's earlier files are removed (nothing
// half-written). Exit 0, 1 (project or photo error, failed render or write), 2 (usage).
#include <cstdio>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "CommandLine.h"
#include "Commands.h"
#include "PhotoDeliverables.h"
#include "ProjectSession.h"
#include "sylva/render/batch/BatchRenderer.h"

namespace sylva::app {
namespace {

constexpr const char* kUsage =
    "usage: sylva montage PROJECT [--only NAME] [--out DIR] [--json] [-D name=value] "
    "[--set block.attr=value]";

}  // namespace

int runMontage(const std::vector<std::string>& originalArguments) {
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
    if (error.empty() && command.positional.size() != 1) {
        error = "montage needs exactly one project file";
    }
    if (!error.empty()) {
        reportError(error + "\n" + kUsage);
        return 2;
    }
    dsl::LoadResult loaded = dsl::loadProject(command.positional[0], loadOptionsFor(command, sets));
    printDiagnostics(loaded);
    if (loaded.hasErrors() || !loaded.model) {
        return 1;
    }
    const std::optional<std::string> only = command.get("only");
    std::optional<std::vector<PlannedPhoto>> photos = planPhotos(
        *loaded.model, only ? std::vector<std::string>{*only} : std::vector<std::string>{}, true);
    if (!photos) {
        return 1;
    }
    render::BatchOptions options;
    options.diskCacheByDefault = true;
    render::BatchRenderer batch(options);
    if (Status set = batch.setProject(scenarioModels(std::move(loaded))); !set) {
        reportError(set.error().message);
        return 1;
    }
    const std::filesystem::path outFolder = command.get("out").value_or(".");
    nlohmann::ordered_json summaries = nlohmann::ordered_json::array();
    if (!makePhotos(batch, *photos, outFolder, summaries)) {
        return 1;
    }
    if (command.has("json")) {
        std::fputs((summaries.dump(2) + "\n").c_str(), stdout);
    }
    return 0;
}

}  // namespace sylva::app
