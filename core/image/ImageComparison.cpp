#include "sylva/core/image/ImageComparison.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

#include "sylva/core/image/BitmapFont.h"
#include "sylva/core/image/ColorDifference.h"
#include "sylva/core/image/ColorSpace.h"
#include "sylva/core/image/ToneMapping.h"

namespace sylva {
namespace {

template <typename Channel>
Status sameSize(const Image<Channel>& a, const Image<Channel>& b) {
    if (a.width != b.width || a.height != b.height) {
        return Error{"cannot compare images of different sizes (" + std::to_string(a.width) + "x" +
                     std::to_string(a.height) + " and " + std::to_string(b.width) + "x" +
                     std::to_string(b.height) + ")"};
    }
    return {};
}

// sRGB byte → linear, through a table (the hot loop of blend()).
const std::array<float, 256>& decodeTable() {
    static const std::array<float, 256> table = [] {
        std::array<float, 256> t{};
        for (int i = 0; i < 256; ++i) {
            t[static_cast<std::size_t>(i)] = srgbToLinear(static_cast<float>(i) / 255.0f);
        }
        return t;
    }();
    return table;
}

// How each image type stores what the comparisons compute: linear colour in and out,
// mixed alpha, and the stored value of a drawn sRGB grey (divider, gutter).
template <typename Channel>
struct Coding;

template <>
struct Coding<std::uint8_t> {
    static float linear(std::uint8_t value) { return decodeTable()[value]; }
    static std::uint8_t encode(float linear) {
        return static_cast<std::uint8_t>(
            std::lround(std::clamp(linearToSrgb(linear), 0.0f, 1.0f) * 255.0f));
    }
    static std::uint8_t alpha(float mixed) { return static_cast<std::uint8_t>(std::lround(mixed)); }
    static std::uint8_t grey(std::uint8_t srgb) { return srgb; }
};

// Radiance is already linear; drawings are stored as the radiance that displays as them.
template <>
struct Coding<float> {
    static float linear(float value) { return value; }
    static float encode(float linear) { return linear; }
    static float alpha(float mixed) { return mixed; }
    static float grey(std::uint8_t srgb) { return ToneMapping::radiance(srgb); }
};

template <typename Channel>
std::array<Channel, 4> greyPixel(std::uint8_t srgb) {
    const Channel value = Coding<Channel>::grey(srgb);
    return {value, value, value, Image<Channel>::kOpaque};
}

int labelScale(const RgbaImage& image) {
    return std::max(1, std::min(image.width, image.height) / 240);
}

// Copies every pixel the 8-bit `overlay` drew (alpha 255) into `image` as radiance.
void applyOverlay(LinearImage& image, const RgbaImage& overlay) {
    for (int y = 0; y < image.height; ++y) {
        for (int x = 0; x < image.width; ++x) {
            const std::uint8_t* drawn = overlay.at(x, y);
            if (drawn[3] == 255) {
                float* p = image.at(x, y);
                for (int c = 0; c < 3; ++c) {
                    p[c] = ToneMapping::radiance(drawn[c]);
                }
                p[3] = 1.0f;
            }
        }
    }
}

// The legend of a difference image: the heat ramp along the bottom with its scale.
void drawLegend(RgbaImage& out, double maximumDeltaE) {
    const int scale = labelScale(out);
    const int barHeight = 6 * scale;
    const int margin = 4 * scale;
    const int textHeight = BitmapFont::textHeight(scale);
    const int top = out.height - margin - barHeight - textHeight;
    const int left = margin;
    const int right = std::max(left + 1, out.width / 3);
    if (top <= 0 || right <= left + 8) {
        return;
    }
    fillPixels(out, 0, top - margin, right + margin * 6, out.height, {12, 12, 12, 255});
    for (int x = left; x < right; ++x) {
        std::uint8_t rgb[3];
        ImageComparison::heatColor(static_cast<double>(x - left) / (right - 1 - left), rgb);
        fillPixels(out, x, top, x + 1, top + barHeight, {rgb[0], rgb[1], rgb[2], 255});
    }
    const std::uint8_t white[3] = {235, 235, 235};
    char text[32];
    BitmapFont::draw(out, left, top + barHeight + scale, "0", scale, white);
    std::snprintf(text, sizeof text, "%g", maximumDeltaE / 2);
    BitmapFont::draw(out, (left + right) / 2 - BitmapFont::textWidth(text, scale) / 2,
                     top + barHeight + scale, text, scale, white);
    std::snprintf(text, sizeof text, "%g dE00", maximumDeltaE);
    BitmapFont::draw(
        out, right - BitmapFont::textWidth(std::to_string(static_cast<int>(maximumDeltaE)), scale),
        top + barHeight + scale, text, scale, white);
}

}  // namespace

template <typename Channel>
Result<Image<Channel>> ImageComparison::blend(const Image<Channel>& from, const Image<Channel>& to,
                                              double amount) {
    if (Status size = sameSize(from, to); !size) {
        return size.error();
    }
    if (!(amount >= 0.0 && amount <= 1.0)) {
        return Error{"blend amount must be within [0, 1]"};
    }
    using Code = Coding<Channel>;
    Image<Channel> out(from.width, from.height);
    const float t = static_cast<float>(amount);
    for (std::size_t i = 0; i < out.pixels.size(); i += 4) {
        for (std::size_t c = 0; c < 3; ++c) {
            out.pixels[i + c] = Code::encode((1.0f - t) * Code::linear(from.pixels[i + c]) +
                                             t * Code::linear(to.pixels[i + c]));
        }
        out.pixels[i + 3] = Code::alpha((1.0f - t) * from.pixels[i + 3] + t * to.pixels[i + 3]);
    }
    return out;
}

template <typename Channel>
Result<Image<Channel>> ImageComparison::sideBySide(const Image<Channel>& left,
                                                   const Image<Channel>& right, int gap) {
    if (left.height != right.height) {
        return Error{"side-by-side images need equal heights (" + std::to_string(left.height) +
                     " and " + std::to_string(right.height) + ")"};
    }
    gap = std::max(gap, 0);
    const Channel gutter = Coding<Channel>::grey(16);
    Image<Channel> out(left.width + gap + right.width, left.height, gutter, gutter, gutter);
    copyPixels(left, 0, 0, left.width, left.height, out, 0, 0);
    copyPixels(right, 0, 0, right.width, right.height, out, left.width + gap, 0);
    return out;
}

template <typename Channel>
Result<Image<Channel>> ImageComparison::swipe(const Image<Channel>& left,
                                              const Image<Channel>& right, double split) {
    if (Status size = sameSize(left, right); !size) {
        return size.error();
    }
    if (!(split >= 0.0 && split <= 1.0)) {
        return Error{"swipe split must be within [0, 1]"};
    }
    Image<Channel> out = right;
    const int divider = static_cast<int>(std::lround(split * left.width));
    copyPixels(left, 0, 0, divider, left.height, out, 0, 0);
    // A light line with dark edges stays visible on bright and dark content.
    const int half = std::max(1, left.width / 640);
    fillPixels(out, divider - half - 1, 0, divider - half, out.height, greyPixel<Channel>(32));
    fillPixels(out, divider - half, 0, divider + half, out.height, greyPixel<Channel>(240));
    fillPixels(out, divider + half, 0, divider + half + 1, out.height, greyPixel<Channel>(32));
    return out;
}

// The two image types ImageComparison serves (the header's promise).
template Result<RgbaImage> ImageComparison::blend(const RgbaImage&, const RgbaImage&, double);
template Result<LinearImage> ImageComparison::blend(const LinearImage&, const LinearImage&, double);
template Result<RgbaImage> ImageComparison::sideBySide(const RgbaImage&, const RgbaImage&, int);
template Result<LinearImage> ImageComparison::sideBySide(const LinearImage&, const LinearImage&,
                                                         int);
template Result<RgbaImage> ImageComparison::swipe(const RgbaImage&, const RgbaImage&, double);
template Result<LinearImage> ImageComparison::swipe(const LinearImage&, const LinearImage&, double);

void ImageComparison::heatColor(double t, std::uint8_t rgb[3]) {
    // Piecewise-linear ramp through perceptually ordered stops (dark to bright).
    static constexpr double kStops[5][4] = {{0.00, 0, 0, 4},
                                            {0.25, 87, 16, 110},
                                            {0.50, 188, 55, 84},
                                            {0.75, 249, 142, 9},
                                            {1.00, 252, 255, 164}};
    t = std::clamp(t, 0.0, 1.0);
    int i = 0;
    while (i < 3 && t > kStops[i + 1][0]) {
        ++i;
    }
    const double s = (t - kStops[i][0]) / (kStops[i + 1][0] - kStops[i][0]);
    for (int c = 0; c < 3; ++c) {
        rgb[c] = static_cast<std::uint8_t>(
            std::lround(kStops[i][c + 1] + s * (kStops[i + 1][c + 1] - kStops[i][c + 1])));
    }
}

Result<RgbaImage> ImageComparison::difference(const RgbaImage& first, const RgbaImage& second,
                                              double maximumDeltaE) {
    if (Status size = sameSize(first, second); !size) {
        return size.error();
    }
    if (!(maximumDeltaE > 0.0)) {
        return Error{"difference scale must be positive"};
    }
    RgbaImage out(first.width, first.height);
    for (int y = 0; y < out.height; ++y) {
        for (int x = 0; x < out.width; ++x) {
            const std::uint8_t* a = first.at(x, y);
            const std::uint8_t* b = second.at(x, y);
            double deltaE = 0.0;
            if (a[0] != b[0] || a[1] != b[1] || a[2] != b[2]) {
                deltaE =
                    ColorDifference::deltaE2000(ColorDifference::labFromSrgb8(a[0], a[1], a[2]),
                                                ColorDifference::labFromSrgb8(b[0], b[1], b[2]));
            }
            heatColor(deltaE / maximumDeltaE, out.at(x, y));
        }
    }
    drawLegend(out, maximumDeltaE);
    return out;
}

Result<LinearImage> ImageComparison::difference(const LinearImage& first, const LinearImage& second,
                                                double maximumDeltaE) {
    if (Status size = sameSize(first, second); !size) {
        return size.error();
    }
    // ΔE is a difference of perceived colours, so it is taken between the displayed
    // images; the heat map is a drawing and is stored as the radiance that shows it.
    Result<RgbaImage> heat =
        difference(ToneMapping::display(first), ToneMapping::display(second), maximumDeltaE);
    if (!heat) {
        return heat.error();
    }
    LinearImage out(first.width, first.height);
    applyOverlay(out, heat.value());
    return out;
}

void ImageComparison::label(LinearImage& image, const std::string& text, bool rightAligned) {
    RgbaImage overlay(image.width, image.height, 0, 0, 0, 0);
    label(overlay, text, rightAligned);
    applyOverlay(image, overlay);
}

void ImageComparison::label(RgbaImage& image, const std::string& text, bool rightAligned) {
    const int scale = labelScale(image) + 1;
    const int margin = 4 * scale;
    const int width = BitmapFont::textWidth(text, scale);
    const int x = rightAligned ? image.width - margin - width : margin;
    const std::uint8_t white[3] = {245, 245, 245};
    const std::uint8_t box[3] = {20, 20, 20};
    BitmapFont::draw(image, x, margin, text, scale, white, box);
}

}  // namespace sylva
