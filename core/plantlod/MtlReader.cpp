#include "MtlReader.h"

#include <optional>

#include "ImportedPlant.h"
#include "ObjTokens.h"
#include "sylva/core/image/ImageWriter.h"

namespace sylva::plantimport {

namespace {

Result<PlantTexture> readTexture(const std::filesystem::path& library, int line,
                                 const std::filesystem::path& file) {
    std::error_code error;
    if (!std::filesystem::exists(file, error)) {
        return Error{library.string() + ":" + std::to_string(line) + ": texture '" + file.string() +
                     "' not found"};
    }
    PlantTexture texture;
    Result<std::vector<std::uint8_t>> pixels =
        ImageWriter::readRgba8(file, texture.width, texture.height);
    if (!pixels) {
        return Error{library.string() + ":" + std::to_string(line) + ": " + pixels.error().message};
    }
    texture.rgba = std::move(*pixels);
    return texture;
}

// map_d: the opacity map, from its alpha channel when it has one, else its grey, sampled
// nearest onto the base texture (a white one of the map's size when there is none).
void applyAlphaMap(PlantMaterial& material, const PlantTexture& alphaMap) {
    PlantTexture& base = material.baseColorTexture;
    const bool ownAlpha = textureHasAlpha(alphaMap);
    if (base.width == 0) {
        base.width = alphaMap.width;
        base.height = alphaMap.height;
        base.rgba.assign(alphaMap.rgba.size(), 255);
    }
    for (int y = 0; y < base.height; ++y) {
        for (int x = 0; x < base.width; ++x) {
            const int ax = x * alphaMap.width / base.width;
            const int ay = y * alphaMap.height / base.height;
            const std::size_t source =
                (std::size_t(ay) * std::size_t(alphaMap.width) + std::size_t(ax)) * 4;
            base.rgba[(std::size_t(y) * std::size_t(base.width) + std::size_t(x)) * 4 + 3] =
                alphaMap.rgba[source + (ownAlpha ? 3 : 0)];
        }
    }
    material.alphaMasked = true;
}

class MtlReader {
public:
    MtlReader(const std::filesystem::path& library, std::vector<PlantMaterial>& materials,
              std::map<std::string, int>& byName)
        : library_(library), materials_(materials), byName_(byName) {}

    Status statement(const std::vector<std::string>& words, int number) {
        const std::string where = library_.string() + ":" + std::to_string(number) + ": ";
        const std::string& keyword = words[0];
        if (keyword == "newmtl") {
            finishMaterial();
            if (words.size() < 2) {
                return Error{where + "newmtl needs a name"};
            }
            byName_[words[1]] = int(materials_.size());
            materials_.emplace_back();
            materials_.back().name = words[1];
            current_ = &materials_.back();
            return Status::success();
        }
        if (current_ == nullptr) {
            return Status::success();  // statements before the first newmtl apply to nothing
        }
        if (keyword == "Kd") {
            glm::vec3 colour;
            if (words.size() < 4 || !parseFloat(words[1], colour.r) ||
                !parseFloat(words[2], colour.g) || !parseFloat(words[3], colour.b)) {
                return Error{where + "Kd needs three numbers"};
            }
            current_->baseColor = glm::vec4(colour, current_->baseColor.a);
        } else if (keyword == "d" || keyword == "Tr") {
            float value;
            if (words.size() < 2 || !parseFloat(words.back(), value)) {
                return Error{where + keyword + " needs a number"};
            }
            current_->baseColor.a = keyword == "d" ? value : 1.0f - value;
        } else if (keyword == "map_Kd" || keyword == "map_d") {
            return map(words, number, where);
        }
        return Status::success();
    }

    // The alpha map of the current material, once its statements are all read.
    void finishMaterial() {
        if (current_ != nullptr && alphaMap_) {
            applyAlphaMap(*current_, *alphaMap_);
        }
        alphaMap_.reset();
    }

private:
    Status map(const std::vector<std::string>& words, int number, const std::string& where) {
        const std::string& keyword = words[0];
        const std::string name = mapFileName(words);
        if (name.empty()) {
            return Error{where + keyword + " needs a file name"};
        }
        Result<PlantTexture> texture = readTexture(library_, number, library_.parent_path() / name);
        if (!texture) {
            return texture.error();
        }
        if (keyword == "map_Kd") {
            current_->baseColorTexture = std::move(*texture);
        } else {
            alphaMap_ = std::move(*texture);
        }
        return Status::success();
    }

    const std::filesystem::path& library_;
    std::vector<PlantMaterial>& materials_;
    std::map<std::string, int>& byName_;
    PlantMaterial* current_ = nullptr;
    std::optional<PlantTexture> alphaMap_;
};

}  // namespace

Status readMtlLibrary(const std::filesystem::path& library, std::vector<PlantMaterial>& materials,
                      std::map<std::string, int>& byName) {
    Result<std::string> text = readWholeFile(library);
    if (!text) {
        return text.error();
    }
    MtlReader reader(library, materials, byName);
    if (Status read =
            forEachStatement(*text, [&](const std::vector<std::string>& words,
                                        int number) { return reader.statement(words, number); });
        !read) {
        return read;
    }
    reader.finishMaterial();
    return Status::success();
}

}  // namespace sylva::plantimport
