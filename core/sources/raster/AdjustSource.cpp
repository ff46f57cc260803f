#include "sylva/core/sources/raster/AdjustSource.h"

#include <algorithm>
#include <cmath>

#include "sylva/core/base/Hash.h"
#include "sylva/core/image/ColorSpace.h"

namespace sylva {

AdjustSource::AdjustSource(std::string name, const Source* input,
                           const AdjustParameters& parameters)
    : Source(std::move(name), "adjust", PortType::Image, input->channels()),
      input_(input),
      parameters_(parameters) {
    SYLVA_CHECK(input->output() == PortType::Image);
    addInput(input);
    const AdjustParameters& p = parameters_;
    setParameterHash(ContentHash()
                         .add(p.brightness)
                         .add(p.contrast)
                         .add(p.saturation)
                         .add(p.hue)
                         .add(p.gamma)
                         .add(p.black)
                         .add(p.white)
                         .value());
}

glm::vec3 AdjustSource::apply(const glm::vec3& linear) const {
    const AdjustParameters& p = parameters_;
    glm::dvec3 c(linearToSrgb(linear.x), linearToSrgb(linear.y), linearToSrgb(linear.z));
    const double range = std::max(p.white - p.black, 1e-6);
    for (int i = 0; i < 3; ++i) {
        double v = std::clamp((c[i] - p.black) / range, 0.0, 1.0);
        v = std::pow(v, 1.0 / p.gamma);
        v += p.brightness;
        v = (v - 0.5) * p.contrast + 0.5;
        c[i] = v;
    }
    const glm::dvec3 lumaWeights(0.2126, 0.7152, 0.0722);
    const double luma = glm::dot(c, lumaWeights);
    glm::dvec3 chroma = c - glm::dvec3(luma);
    if (p.hue != 0.0) {
        // Rodrigues' rotation of the chroma about the grey axis, then restore the luma.
        const glm::dvec3 axis = glm::normalize(glm::dvec3(1.0));
        const double cs = std::cos(p.hue), sn = std::sin(p.hue);
        chroma = chroma * cs + glm::cross(axis, chroma) * sn +
                 axis * glm::dot(axis, chroma) * (1.0 - cs);
        const glm::dvec3 rotated = glm::dvec3(luma) + chroma;
        chroma = rotated - glm::dvec3(glm::dot(rotated, lumaWeights));
    }
    c = glm::dvec3(luma) + chroma * p.saturation;
    return {srgbToLinear(static_cast<float>(std::clamp(c.x, 0.0, 1.0))),
            srgbToLinear(static_cast<float>(std::clamp(c.y, 0.0, 1.0))),
            srgbToLinear(static_cast<float>(std::clamp(c.z, 0.0, 1.0)))};
}

Result<TilePointer> AdjustSource::produce(const TileKey& key, TileProvider& provider) const {
    Result<TilePointer> input = provider.tile(*input_, key);
    if (!input) {
        return input.error();
    }
    auto tile = std::make_shared<ImageTile>(*input.value());
    const int channels = tile->channels();
    std::vector<float>& texels = tile->texels();
    for (std::size_t i = 0; i + 2 < texels.size(); i += static_cast<std::size_t>(channels)) {
        const glm::vec3 out = apply({texels[i], texels[i + 1], texels[i + 2]});
        texels[i] = out.x;
        texels[i + 1] = out.y;
        texels[i + 2] = out.z;
    }
    return TilePointer(std::move(tile));
}

Result<std::unique_ptr<Source>> AdjustSource::create(const SourceBuildContext& context) {
    const BlockReader& reader = context.reader;
    Result<const Source*> input = context.input("input", true);
    if (!input) {
        return input.error();
    }
    if (input.value()->output() != PortType::Image || input.value()->channels() < 3) {
        return Error{reader.where("input") + "'input' expects an image, but source '" +
                     input.value()->name() + "' gives " + portTypeName(input.value()->output())};
    }
    AdjustParameters p;
    for (auto [name, target] : {std::pair{"brightness", &p.brightness},
                                {"contrast", &p.contrast},
                                {"saturation", &p.saturation},
                                {"hue", &p.hue},
                                {"gamma", &p.gamma},
                                {"black", &p.black},
                                {"white", &p.white}}) {
        if (std::optional<double> v = reader.optionalNumber(name)) {
            *target = *v;
        }
    }
    if (p.gamma <= 0.0) {
        return Error{reader.where("gamma") + "gamma must be positive"};
    }
    return std::unique_ptr<Source>(
        std::make_unique<AdjustSource>(context.block.name, input.value(), p));
}

}  // namespace sylva
