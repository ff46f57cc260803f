// Conversions between sRGB-encoded and linear RGB components (IEC 61966-2-1 curve).
// Project files write colours in sRGB; tiles and shading work in linear RGB; 8-bit
// output images are sRGB again.
#pragma once

#include <cmath>

namespace sylva {

inline float srgbToLinear(float encoded) {
    return encoded <= 0.04045f ? encoded / 12.92f : std::pow((encoded + 0.055f) / 1.055f, 2.4f);
}

inline float linearToSrgb(float linear) {
    if (linear <= 0.0f) {
        return 0.0f;
    }
    return linear <= 0.0031308f ? linear * 12.92f : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
}

}  // namespace sylva
