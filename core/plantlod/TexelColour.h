// TexelColour: 8-bit sRGB texel components (plant textures, atlases, rasterized images)
// to and from linear light, on the curve of ColorSpace.h.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "sylva/core/image/ColorSpace.h"

namespace sylva {

inline float texelToLinear(std::uint8_t value) {
    return srgbToLinear(float(value) / 255.0f);
}

// Clamped to [0, 1], rounded to the nearest code.
inline std::uint8_t linearToTexel(float linear) {
    return std::uint8_t(std::lround(std::clamp(linearToSrgb(linear), 0.0f, 1.0f) * 255.0f));
}

}  // namespace sylva
