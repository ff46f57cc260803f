// PlantSidecar: `<model stem>.plant.json` next to a plant model file (`tree.glb` →
// `tree.plant.json`), which names the part of meshes the importer's other rules would
// misjudge: {"parts": {NAME: "leaf" | "branch", ...}}, NAME matching a material, mesh or
// node name (docs/plants.md, "Sidecar"). The first rule of the leaf/branch split.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>

#include "sylva/core/base/Result.h"
#include "sylva/core/plantlod/PlantModel.h"

namespace sylva {

class PlantSidecar {
public:
    // Where the sidecar of `model` lives (whether or not it exists).
    static std::filesystem::path pathFor(const std::filesystem::path& model);

    // The sidecar of `model`; no parts when there is none. Fails, naming the sidecar and
    // the key, on unreadable files, invalid JSON, a missing "parts" object or a value
    // other than "leaf" or "branch".
    static Result<PlantSidecar> readFor(const std::filesystem::path& model);

    // The part the sidecar gives `name`; nothing for an empty or unlisted name.
    std::optional<PlantPart> partOf(const std::string& name) const;

private:
    std::map<std::string, PlantPart> parts_;
};

}  // namespace sylva
