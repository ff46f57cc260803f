// ImageComparison: the comparison images of scenario pairs (issue: scenarios and
// comparisons). For PNG series, inputs and outputs are RgbaImages (sRGB-encoded, 8 bit);
// mixing happens in linear light, so a 50 % blend of black and white is mid-grey in
// radiance (sRGB 188), as a cross-fade of two photographs would be.
//
// The LinearImage versions compose EXR (linear radiance) images in float: blend mixes
// radiance, swipe and side_by_side copy it; everything drawn (divider, gutter, labels,
// the difference heat map and its legend) is stored as the radiance that tone-maps
// (ToneMapping) to the colour the 8-bit version draws, so an EXR comparison displays as
// its PNG twin. The difference of two EXRs is the ΔE of their displayed colours.
//
// Errors (Result): images of different sizes, parameters out of range.
#pragma once

#include <string>

#include "sylva/core/base/Result.h"
#include "sylva/core/image/Image.h"

namespace sylva {

class ImageComparison {
public:
    // blend, sideBySide and swipe are written once for both image types and instantiated
    // for RgbaImage (Channel = std::uint8_t) and LinearImage (Channel = float) only.

    // (1 − amount) · from + amount · to, per pixel in linear RGB (alpha mixed as stored);
    // amount in [0, 1].
    template <typename Channel>
    static Result<Image<Channel>> blend(const Image<Channel>& from, const Image<Channel>& to,
                                        double amount);
    // The two images next to each other with a `gap` pixel dark gutter between them.
    template <typename Channel>
    static Result<Image<Channel>> sideBySide(const Image<Channel>& left,
                                             const Image<Channel>& right, int gap = 4);
    // Left image up to split · width, right image beyond, with a light divider line.
    template <typename Channel>
    static Result<Image<Channel>> swipe(const Image<Channel>& left, const Image<Channel>& right,
                                        double split);
    // Per-pixel CIEDE2000 between the images as a heat map (black → purple → orange →
    // yellow at `maximumDeltaE` and above), with a legend bar and its scale drawn along
    // the bottom edge.
    static Result<RgbaImage> difference(const RgbaImage& first, const RgbaImage& second,
                                        double maximumDeltaE = 20.0);
    static Result<LinearImage> difference(const LinearImage& first, const LinearImage& second,
                                          double maximumDeltaE = 20.0);

    // The heat-map colour (sRGB 8-bit) of a normalised difference t in [0, 1].
    static void heatColor(double t, std::uint8_t rgb[3]);
    // Draws a caption in the top-left (`rightAligned`: top-right) corner on a dark box.
    static void label(RgbaImage& image, const std::string& text, bool rightAligned = false);
    static void label(LinearImage& image, const std::string& text, bool rightAligned = false);
};

}  // namespace sylva
