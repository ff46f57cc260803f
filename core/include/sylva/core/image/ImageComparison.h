// ImageComparison: the comparison images of scenario pairs (issue: scenarios and
// comparisons). All inputs and outputs are RgbaImages (sRGB-encoded, 8 bit). Mixing
// happens in linear light, so a 50 % blend of black and white is mid-grey in
// radiance (sRGB 188), as a cross-fade of two photographs would be.
//
// The LinearImage overloads compose EXR (linear radiance) images in float: blend mixes
// radiance, swipe and side_by_side copy it; everything drawn (divider, gutter, labels,
// the difference heat map and its legend) is stored as the radiance that tone-maps
// (ToneMapping) to the colour the 8-bit version draws, so an EXR comparison displays as
// its PNG twin. The difference of two EXRs is the ΔE of their displayed colours.
//
// Errors (Result): images of different sizes, parameters out of range.
#pragma once

#include <string>

#include "sylva/core/base/Result.h"
#include "sylva/core/image/LinearImage.h"
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
    static Result<LinearImage> blend(const LinearImage& from, const LinearImage& to, double amount);
    static Result<LinearImage> sideBySide(const LinearImage& left, const LinearImage& right,
                                          int gap = 4);
    static Result<LinearImage> swipe(const LinearImage& left, const LinearImage& right,
                                     double split);
    static Result<LinearImage> difference(const LinearImage& first, const LinearImage& second,
                                          double maximumDeltaE = 20.0);
    static void label(LinearImage& image, const std::string& text, bool rightAligned = false);

    // The heat-map colour (sRGB 8-bit) of a normalised difference t in [0, 1].
    static void heatColor(double t, std::uint8_t rgb[3]);
    // Draws a caption in the top-left (`rightAligned`: top-right) corner on a dark box.
    static void label(RgbaImage& image, const std::string& text, bool rightAligned = false);
};

}  // namespace sylva
