#include "sylva/core/image/ToneMapping.h"

#include <algorithm>
#include <cmath>

#include "sylva/core/image/ColorSpace.h"

namespace sylva {

std::uint8_t ToneMapping::display(float radiance) {
    const float mapped = 1.0f - std::exp(-std::max(radiance, 0.0f));
    return static_cast<std::uint8_t>(
        std::lround(std::clamp(linearToSrgb(mapped), 0.0f, 1.0f) * 255.0f));
}

RgbaImage ToneMapping::display(const LinearImage& image) {
    RgbaImage out(image.width, image.height);
    for (std::size_t i = 0; i < image.pixels.size(); i += 4) {
        for (std::size_t c = 0; c < 3; ++c) {
            out.pixels[i + c] = display(image.pixels[i + c]);
        }
        out.pixels[i + 3] = static_cast<std::uint8_t>(
            std::lround(std::clamp(image.pixels[i + 3], 0.0f, 1.0f) * 255.0f));
    }
    return out;
}

float ToneMapping::radiance(std::uint8_t srgb) {
    const float mapped =
        std::min(srgbToLinear(static_cast<float>(srgb) / 255.0f), 1.0f - 1.0f / 4096.0f);
    return -std::log1p(-mapped);
}

LinearImage ToneMapping::radiance(const RgbaImage& image) {
    LinearImage out(image.width, image.height);
    for (std::size_t i = 0; i < out.pixels.size(); ++i) {
        out.pixels[i] = i % 4 == 3 ? image.pixels[i] / 255.0f : radiance(image.pixels[i]);
    }
    return out;
}

}  // namespace sylva
