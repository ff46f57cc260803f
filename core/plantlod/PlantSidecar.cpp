#include "sylva/core/plantlod/PlantSidecar.h"

#include <nlohmann/json.hpp>

#include "ImportedPlant.h"

namespace sylva {

std::filesystem::path PlantSidecar::pathFor(const std::filesystem::path& model) {
    return model.parent_path() / (model.stem().string() + ".plant.json");
}

Result<PlantSidecar> PlantSidecar::readFor(const std::filesystem::path& model) {
    using Json = nlohmann::json;
    const std::filesystem::path path = pathFor(model);
    PlantSidecar sidecar;
    std::error_code error;
    if (!std::filesystem::exists(path, error)) {
        return sidecar;
    }
    Result<std::string> text = plantimport::readWholeFile(path);
    if (!text) {
        return text.error();
    }
    Json json;
    try {
        json = Json::parse(*text);
    } catch (const Json::parse_error& e) {
        return Error{path.string() + ": invalid JSON at byte " + std::to_string(e.byte)};
    }
    if (!json.is_object() || !json.contains("parts") || !json["parts"].is_object()) {
        return Error{path.string() + ": expected an object with a \"parts\" object"};
    }
    for (const auto& [name, value] : json["parts"].items()) {
        if (value == "leaf") {
            sidecar.parts_[name] = PlantPart::Leaf;
        } else if (value == "branch") {
            sidecar.parts_[name] = PlantPart::Branch;
        } else {
            return Error{path.string() + ": parts." + name + ": must be \"leaf\" or \"branch\""};
        }
    }
    return sidecar;
}

std::optional<PlantPart> PlantSidecar::partOf(const std::string& name) const {
    if (auto it = parts_.find(name); !name.empty() && it != parts_.end()) {
        return it->second;
    }
    return std::nullopt;
}

}  // namespace sylva
