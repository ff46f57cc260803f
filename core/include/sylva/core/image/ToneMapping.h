// ToneMapping: the CPU copy of the shading pass's display transform (shaders/shading/
// shade.frag): display = sRGB(1 − exp(−radiance)), where radiance already includes the
// exposure. Used to show EXR (linear) images as 8-bit sRGB (contact sheets, comparison
// overlays) and by tests that check an EXR against the PNG of the same view.
#pragma once

#include <cstdint>

#include "sylva/core/image/Image.h"

namespace sylva {

class ToneMapping {
public:
    // One channel: exposed radiance → sRGB byte (negative radiance maps to 0).
    static std::uint8_t display(float radiance);
    // The whole image; alpha is copied (× 255).
    static RgbaImage display(const LinearImage& image);
    // The inverse for drawn overlays (labels, dividers, heat maps): the radiance that
    // displays as this sRGB byte. 255 maps to a finite radiance (1 − 2⁻¹² on the curve).
    static float radiance(std::uint8_t srgb);
    // The whole image (alpha ÷ 255): an 8-bit image as the radiance that displays as it.
    static LinearImage radiance(const RgbaImage& image);
};

}  // namespace sylva
