#include "sylva/core/scene/RenderManifest.h"

#include "sylva/core/base/AtomicFile.h"

#include <unistd.h>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <system_error>

#include <nlohmann/json.hpp>

namespace sylva {
namespace {

std::string hex(std::uint64_t value) {
    char text[20];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(value));
    return text;
}

}  // namespace

Status RenderManifest::load() {
    entries_.clear();
    std::error_code error;
    if (!std::filesystem::exists(file_, error)) {
        return {};
    }
    std::ifstream in(file_);
    if (!in) {
        return Error{"cannot read manifest '" + file_.string() + "'"};
    }
    std::stringstream text;
    text << in.rdbuf();
    nlohmann::json json = nlohmann::json::parse(text.str(), nullptr, /*allow_exceptions=*/false);
    if (json.is_discarded() || !json.is_object() || !json.contains("images") ||
        !json["images"].is_array()) {
        return Error{"manifest '" + file_.string() +
                     "' is corrupt (not a Sylva manifest): delete it to render everything"};
    }
    for (const nlohmann::json& image : json["images"]) {
        if (!image.is_object() || !image.contains("output") || !image["output"].is_string() ||
            !image.contains("hash") || !image["hash"].is_string()) {
            return Error{"manifest '" + file_.string() + "' has an entry without output or hash"};
        }
        ManifestEntry entry;
        entry.output = image["output"].get<std::string>();
        entry.hash = std::strtoull(image["hash"].get<std::string>().c_str(), nullptr, 16);
        auto field = [&](const char* key) {
            return image.contains(key) && image[key].is_string() ? image[key].get<std::string>()
                                                                 : std::string();
        };
        entry.view = field("view");
        entry.camera = field("camera");
        entry.path = field("path");
        entry.scenario = field("scenario");
        entry.time = field("time");
        entry.kind = field("kind");
        entry.frame = image.value("frame", -1);
        entry.seconds = image.value("seconds", 0.0);
        entry.tilesGenerated = image.value("tiles_generated", std::uint64_t{0});
        entries_[entry.output] = entry;
    }
    return {};
}

Status RenderManifest::save() const {
    nlohmann::ordered_json json;
    json["format"] = "sylva-render-manifest";
    json["version"] = 1;
    nlohmann::ordered_json images = nlohmann::ordered_json::array();
    for (const auto& [output, entry] : entries_) {
        nlohmann::ordered_json image;
        image["output"] = entry.output;
        image["kind"] = entry.kind;
        image["view"] = entry.view;
        if (!entry.camera.empty()) {
            image["camera"] = entry.camera;
        }
        if (!entry.path.empty()) {
            image["path"] = entry.path;
            image["frame"] = entry.frame;
        }
        image["scenario"] = entry.scenario;
        if (!entry.time.empty()) {
            image["time"] = entry.time;
        }
        image["hash"] = hex(entry.hash);
        image["seconds"] = entry.seconds;
        image["tiles_generated"] = entry.tilesGenerated;
        images.push_back(std::move(image));
    }
    json["images"] = std::move(images);

    std::error_code error;
    if (file_.has_parent_path()) {
        std::filesystem::create_directories(file_.parent_path(), error);
    }
    const Status written = writeFileAtomically(file_, json.dump(2) + "\n");
    if (!written) {
        return Error{"cannot write manifest '" + file_.string() + "': " + written.error().message};
    }
    return {};
}

bool RenderManifest::isCurrent(const std::string& output, std::uint64_t hash) const {
    auto found = entries_.find(output);
    if (found == entries_.end() || found->second.hash != hash) {
        return false;
    }
    std::error_code error;
    const std::filesystem::path image = file_.parent_path() / output;
    return std::filesystem::is_regular_file(image, error) &&
           std::filesystem::file_size(image, error) > 0;
}

}  // namespace sylva
