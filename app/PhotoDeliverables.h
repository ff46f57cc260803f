// PhotoDeliverables: the files of `photo` blocks (issue 18; LI TGN 06/19 Types 2–4), shared
// by `sylva montage` (every photo block, or one) and `sylva render` (the photo blocks a
// views block names in `photos`, so a viewpoint pack comes from one command).
//
// planPhotos reads every selected block and its photograph first, so a located error in
// any of them stops the command before anything renders. makePhotos renders each
// (render::PhotomontageRenderer) and writes PREFIX_montage.png, PREFIX_wireline.png,
// PREFIX_model.png and PREFIX.json (with `sheet` also PREFIX.sheet.pdf/.png and
// PREFIX_map.png), each atomically; when one write fails, the block's earlier files are
// removed (nothing half-written). Errors are printed ("sylva: ..." on stderr).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "sylva/core/image/PhotoReader.h"
#include "sylva/core/model/ProjectModel.h"
#include "sylva/core/scene/PhotoViewpoint.h"
#include "sylva/render/batch/BatchRenderer.h"

namespace sylva::app {

struct PlannedPhoto {
    PhotoViewpoint viewpoint;
    Photo picture;
};

// The photo blocks named in `names` (every one when `names` is empty), each read and its
// photograph loaded; nullopt after reporting every failure. `requireAny`: a project
// without a (matching) photo block is an error.
std::optional<std::vector<PlannedPhoto>> planPhotos(const ProjectModel& model,
                                                    const std::vector<std::string>& names,
                                                    bool requireAny);

// Renders and writes every planned photo under `outFolder`; false after reporting the
// first failure (the files of the blocks done before it stay: each block is whole).
// `summaries` receives one JSON summary per block (`sylva montage --json`).
bool makePhotos(render::BatchRenderer& batch, const std::vector<PlannedPhoto>& photos,
                const std::filesystem::path& outFolder, nlohmann::ordered_json& summaries);

}  // namespace sylva::app
