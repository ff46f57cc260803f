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

Status sameSize(const RgbaImage& a, const RgbaImage& b) {
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

std::uint8_t encode(float linear) {
    return static_cast<std::uint8_t>(
        std::lround(std::clamp(linearToSrgb(linear), 0.0f, 1.0f) * 255.0f));
}

template <typename Image>
int labelScale(const Image& image) {
    return std::max(1, std::min(image.width, image.height) / 240);
}

Status sameSize(const LinearImage& a, const LinearImage& b) {
    if (a.width != b.width || a.height != b.height) {
        return Error{"cannot compare images of different sizes (" + std::to_string(a.width) + "x" +
                     std::to_string(a.height) + " and " + std::to_string(b.width) + "x" +
                     std::to_string(b.height) + ")"};
    }
    return {};
}

// The radiance that displays as this sRGB grey (for drawn overlays).
void setGrey(float* pixel, std::uint8_t srgb) {
    pixel[0] = pixel[1] = pixel[2] = ToneMapping::radiance(srgb);
    pixel[3] = 1.0f;
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

}  // namespace

Result<RgbaImage> ImageComparison::blend(const RgbaImage& from, const RgbaImage& to,
                                         double amount) {
    if (Status size = sameSize(from, to); !size) {
        return size.error();
    }
    if (!(amount >= 0.0 && amount <= 1.0)) {
        return Error{"blend amount must be within [0, 1]"};
    }
    const auto& decode = decodeTable();
    RgbaImage out(from.width, from.height);
    const float t = static_cast<float>(amount);
    for (std::size_t i = 0; i < out.pixels.size(); i += 4) {
        for (std::size_t c = 0; c < 3; ++c) {
            const float mixed =
                (1.0f - t) * decode[from.pixels[i + c]] + t * decode[to.pixels[i + c]];
            out.pixels[i + c] = encode(mixed);
        }
        out.pixels[i + 3] = static_cast<std::uint8_t>(
            std::lround((1.0f - t) * from.pixels[i + 3] + t * to.pixels[i + 3]));
    }
    return out;
}

Result<RgbaImage> ImageComparison::sideBySide(const RgbaImage& left, const RgbaImage& right,
                                              int gap) {
    if (left.height != right.height) {
        return Error{"side-by-side images need equal heights (" + std::to_string(left.height) +
                     " and " + std::to_string(right.height) + ")"};
    }
    gap = std::max(gap, 0);
    RgbaImage out(left.width + gap + right.width, left.height, 16, 16, 16);
    for (int y = 0; y < out.height; ++y) {
        std::copy_n(left.at(0, y), static_cast<std::size_t>(left.width) * 4, out.at(0, y));
        std::copy_n(right.at(0, y), static_cast<std::size_t>(right.width) * 4,
                    out.at(left.width + gap, y));
    }
    return out;
}

Result<RgbaImage> ImageComparison::swipe(const RgbaImage& left, const RgbaImage& right,
                                         double split) {
    if (Status size = sameSize(left, right); !size) {
        return size.error();
    }
    if (!(split >= 0.0 && split <= 1.0)) {
        return Error{"swipe split must be within [0, 1]"};
    }
    RgbaImage out = right;
    const int divider = static_cast<int>(std::lround(split * left.width));
    for (int y = 0; y < out.height; ++y) {
        std::copy_n(left.at(0, y), static_cast<std::size_t>(divider) * 4, out.at(0, y));
    }
    // A light line with dark edges stays visible on bright and dark content.
    const int half = std::max(1, left.width / 640);
    for (int y = 0; y < out.height; ++y) {
        for (int x = divider - half - 1; x <= divider + half; ++x) {
            if (x < 0 || x >= out.width) {
                continue;
            }
            const bool edge = x == divider - half - 1 || x == divider + half;
            std::uint8_t* p = out.at(x, y);
            p[0] = p[1] = p[2] = edge ? 32 : 240;
            p[3] = 255;
        }
    }
    return out;
}

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
    // Legend: the ramp along the bottom with its scale.
    const int scale = labelScale(out);
    const int barHeight = 6 * scale;
    const int margin = 4 * scale;
    const int textHeight = BitmapFont::textHeight(scale);
    const int top = out.height - margin - barHeight - textHeight;
    const int left = margin;
    const int right = std::max(left + 1, out.width / 3);
    if (top > 0 && right > left + 8) {
        const std::uint8_t panel[3] = {12, 12, 12};
        for (int y = top - margin; y < out.height; ++y) {
            for (int x = 0; x < right + margin * 6; ++x) {
                if (x < out.width && y >= 0) {
                    std::uint8_t* p = out.at(x, y);
                    std::copy_n(panel, 3, p);
                }
            }
        }
        for (int x = left; x < right; ++x) {
            std::uint8_t rgb[3];
            heatColor(static_cast<double>(x - left) / (right - 1 - left), rgb);
            for (int y = top; y < top + barHeight; ++y) {
                std::copy_n(rgb, 3, out.at(x, y));
            }
        }
        const std::uint8_t white[3] = {235, 235, 235};
        char text[32];
        BitmapFont::draw(out, left, top + barHeight + scale, "0", scale, white);
        std::snprintf(text, sizeof text, "%g", maximumDeltaE / 2);
        BitmapFont::draw(out, (left + right) / 2 - BitmapFont::textWidth(text, scale) / 2,
                         top + barHeight + scale, text, scale, white);
        std::snprintf(text, sizeof text, "%g dE00", maximumDeltaE);
        BitmapFont::draw(
            out,
            right - BitmapFont::textWidth(std::to_string(static_cast<int>(maximumDeltaE)), scale),
            top + barHeight + scale, text, scale, white);
    }
    return out;
}

Result<LinearImage> ImageComparison::blend(const LinearImage& from, const LinearImage& to,
                                           double amount) {
    if (Status size = sameSize(from, to); !size) {
        return size.error();
    }
    if (!(amount >= 0.0 && amount <= 1.0)) {
        return Error{"blend amount must be within [0, 1]"};
    }
    LinearImage out(from.width, from.height);
    const float t = static_cast<float>(amount);
    for (std::size_t i = 0; i < out.pixels.size(); ++i) {
        out.pixels[i] = (1.0f - t) * from.pixels[i] + t * to.pixels[i];
    }
    return out;
}

Result<LinearImage> ImageComparison::sideBySide(const LinearImage& left, const LinearImage& right,
                                                int gap) {
    if (left.height != right.height) {
        return Error{"side-by-side images need equal heights (" + std::to_string(left.height) +
                     " and " + std::to_string(right.height) + ")"};
    }
    gap = std::max(gap, 0);
    const float gutter = ToneMapping::radiance(16);
    LinearImage out(left.width + gap + right.width, left.height, gutter, gutter, gutter);
    for (int y = 0; y < out.height; ++y) {
        std::copy_n(left.at(0, y), static_cast<std::size_t>(left.width) * 4, out.at(0, y));
        std::copy_n(right.at(0, y), static_cast<std::size_t>(right.width) * 4,
                    out.at(left.width + gap, y));
    }
    return out;
}

Result<LinearImage> ImageComparison::swipe(const LinearImage& left, const LinearImage& right,
                                           double split) {
    if (Status size = sameSize(left, right); !size) {
        return size.error();
    }
    if (!(split >= 0.0 && split <= 1.0)) {
        return Error{"swipe split must be within [0, 1]"};
    }
    LinearImage out = right;
    const int divider = static_cast<int>(std::lround(split * left.width));
    for (int y = 0; y < out.height; ++y) {
        std::copy_n(left.at(0, y), static_cast<std::size_t>(divider) * 4, out.at(0, y));
    }
    // The same divider as the 8-bit swipe.
    const int half = std::max(1, left.width / 640);
    for (int y = 0; y < out.height; ++y) {
        for (int x = divider - half - 1; x <= divider + half; ++x) {
            if (x >= 0 && x < out.width) {
                setGrey(out.at(x, y), x == divider - half - 1 || x == divider + half ? 32 : 240);
            }
        }
    }
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
