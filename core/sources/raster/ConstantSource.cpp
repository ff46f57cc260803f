#include "sylva/core/sources/raster/ConstantSource.h"

#include "sylva/core/base/Hash.h"
#include "sylva/core/image/ColorSpace.h"

namespace sylva {

ConstantSource::ConstantSource(std::string name, double height)
    : Source(std::move(name), "constant", PortType::Elevation, 1),
      value_(static_cast<float>(height), 0.0f, 0.0f, 0.0f) {
    setParameterHash(ContentHash().add(1).add(value_.x).value());
}

ConstantSource::ConstantSource(std::string name, const glm::vec4& linearColor)
    : Source(std::move(name), "constant", PortType::Image, 4), value_(linearColor) {
    setParameterHash(
        ContentHash().add(2).add(value_.x).add(value_.y).add(value_.z).add(value_.w).value());
}

Result<TilePointer> ConstantSource::produce(const TileKey& key, TileProvider& provider) const {
    const TileFormat& format = provider.format();
    auto tile = std::make_shared<ImageTile>(key, format.size, format.border, channels());
    std::vector<float>& texels = tile->texels();
    for (std::size_t i = 0; i < texels.size(); i += static_cast<std::size_t>(channels())) {
        for (int c = 0; c < channels(); ++c) {
            texels[i + static_cast<std::size_t>(c)] = value_[c];
        }
    }
    return TilePointer(std::move(tile));
}

Result<std::unique_ptr<Source>> ConstantSource::create(const SourceBuildContext& context) {
    const BlockReader& reader = context.reader;
    const Value* kind = reader.value("kind");
    const Word* word = kind != nullptr ? kind->get<Word>() : nullptr;
    if (word != nullptr && word->text == "image") {
        const Color c = reader.color("color").value_or(Color{0.5f, 0.5f, 0.5f, 1.0f});
        return std::unique_ptr<Source>(std::make_unique<ConstantSource>(
            context.block.name,
            glm::vec4(srgbToLinear(c.r), srgbToLinear(c.g), srgbToLinear(c.b), c.a)));
    }
    return std::unique_ptr<Source>(std::make_unique<ConstantSource>(
        context.block.name, reader.optionalNumber("height").value_or(0.0)));
}

}  // namespace sylva
