// ImageComparison: the comparison images of scenario pairs (issue: scenarios and
// comparisons). All inputs and outputs are RgbaImages (sRGB-encoded, 8 bit). Mixing
// happens in linear light, so a 50 % blend of black and white is mid-grey in
// radiance (sRGB 188), as a cross-fade of two photographs would be.
//
// Errors (Result): images of different sizes, parameters out of range.
#pragma once

#include <string>

#include "sylva/core/base/Result.h"
#include "sylva/core/image/RgbaImage.h"

namespace sylva {

class ImageComparison {
public:
    // (1 − amount) · from + amount · to, per pixel in linear RGB; amount in [0, 1].
    static Result<RgbaImage> blend(const RgbaImage& from, const RgbaImage& to, double amount);
    // The two images next to each other with a `gap` pixel dark gutter between them.
    static Result<RgbaImage> sideBySide(const RgbaImage& left, const RgbaImage& right, int gap = 4);
    // Left image up to split · width, right image beyond, with a light divider line.
    static Result<RgbaImage> swipe(const RgbaImage& left, const RgbaImage& right, double split);
    // Per-pixel CIEDE2000 between the images as a heat map (black → purple → orange →
    // yellow at `maximumDeltaE` and above), with a legend bar and its scale drawn along
    // the bottom edge.
    static Result<RgbaImage> difference(const RgbaImage& first, const RgbaImage& second,
                                        double maximumDeltaE = 20.0);
    // The heat-map colour (sRGB 8-bit) of a normalised difference t in [0, 1].
    static void heatColor(double t, std::uint8_t rgb[3]);
    // Draws a caption in the top-left (`rightAligned`: top-right) corner on a dark box.
    static void label(RgbaImage& image, const std::string& text, bool rightAligned = false);
};

}  // namespace sylva
