// Photomontage: the image operations of a TGN 06/19 Type 3 photomontage and of wireline
// images (Type 2 over a render, Type 3 "photowire" over the photograph): the proposal's
// pixels of a render laid over the photograph, and masks drawn as lines of a width.
// Images are 8-bit sRGB RGBA (Image.h); sizes that differ are programmer errors.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "sylva/core/image/Image.h"
#include "sylva/core/image/ProposalMask.h"

namespace sylva {

// How wirelines are drawn (the photo block's and `compare { mode = wireline }`'s
// wireline_color, skyline_color and line_width).
struct WirelineStyle {
    std::array<std::uint8_t, 4> silhouette{255, 26, 26, 255};  // the proposal's outline, sRGB
    std::array<std::uint8_t, 4> skyline{0, 217, 255, 255};     // the terrain skyline, sRGB
    double width = 3.0;                                        // pixels, >= 1
};

// The masks of a wireline, from the baseline's and the proposed scenario's depth buffers of
// one camera (ProposalMask's conventions): the proposal's visible pixels, their outline,
// the baseline's skyline.
struct WirelineMasks {
    PixelMask proposal, silhouette, skyline;

    static WirelineMasks fromDepths(const std::vector<float>& baseline,
                                    const std::vector<float>& proposed, int width, int height);
};

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
    // A wireline image: the skyline, then the proposal's silhouette over it, drawn into
    // `image` (the photograph: a photowire; the baseline render: TGN Type 2).
    static void drawWireline(RgbaImage& image, const WirelineMasks& masks,
                             const WirelineStyle& style);
};

}  // namespace sylva
