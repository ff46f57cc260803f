// ColorDifference: perceptual colour difference for scenario difference images.
// sRGB (8-bit, D65) → CIE XYZ → CIELAB (D65 white), then CIEDE2000 (Sharma, Wu and
// Dalal 2005, "The CIEDE2000 color-difference formula: implementation notes,
// supplementary test data, and mathematical observations"); tested against their
// published test pairs. ΔE00 ≈ 1 is a just-noticeable difference.
#pragma once

#include <cstdint>

namespace sylva {

struct Lab {
    double lightness = 0;  // L*, 0..100
    double a = 0;
    double b = 0;
};

class ColorDifference {
public:
    static Lab labFromSrgb8(std::uint8_t red, std::uint8_t green, std::uint8_t blue);
    static double deltaE2000(const Lab& first, const Lab& second);
};

}  // namespace sylva
