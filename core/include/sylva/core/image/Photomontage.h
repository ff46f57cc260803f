// Photomontage: the image operations of a TGN 06/19 Type 3 photomontage and of wireline
// images (Type 2 over a render, Type 3 "photowire" over the photograph): the proposal's
// pixels of a render laid over the photograph, and masks drawn as lines of a width.
// Images are 8-bit sRGB RGBA (Image.h); sizes that differ are programmer errors.
#pragma once

#include <array>
#include <cstdint>

#include "sylva/core/image/Image.h"
#include "sylva/core/image/ProposalMask.h"

namespace sylva {

class Photomontage {
public:
    // `photo` with `render`'s pixels where `mask` is set (opaque; the proposal's surfaces
    // are rendered with the matched camera, so they stand where the photograph's would).
    static RgbaImage composite(const RgbaImage& photo, const RgbaImage& render,
                               const PixelMask& mask);
    // Draws every pixel of `lines` into `image` as a disc of diameter `width` pixels in
    // `colour` (sRGB, alpha 255 opaque). Width 1 draws the pixels themselves.
    static void drawLines(RgbaImage& image, const PixelMask& lines,
                          const std::array<std::uint8_t, 4>& colour, double width);
};

}  // namespace sylva
