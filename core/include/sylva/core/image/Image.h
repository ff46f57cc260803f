// Image<Channel>: an RGBA picture on the CPU, 4 interleaved channels per pixel, rows top
// to bottom (width * height * 4 values). The two instantiations Sylva uses say what the
// channel values mean:
//   RgbaImage   = Image<std::uint8_t>: sRGB-encoded colour, linear alpha (0–255), as PNG
//                 files, comparison images and contact sheets store it (the renderer
//                 reads its framebuffer into this layout).
//   LinearImage = Image<float>: linear light, RGB = scene radiance × exposure (the
//                 renderer's value before tone mapping, Rec.709/sRGB primaries, no upper
//                 bound), alpha linear in [0, 1], as Sylva writes EXR files.
// The image owns its pixels (a value type). Coordinates outside the image and blocks that
// do not fit are programmer errors (SYLVA_CHECK aborts).
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <type_traits>
#include <vector>

#include "sylva/core/base/Check.h"

namespace sylva {

template <typename Channel>
struct Image {
    static_assert(std::is_arithmetic_v<Channel>);
    static constexpr int kChannels = 4;
    // The alpha of an opaque pixel: full scale for integers, 1 for floats.
    static constexpr Channel kOpaque =
        std::is_floating_point_v<Channel> ? Channel(1) : std::numeric_limits<Channel>::max();

    int width = 0;
    int height = 0;
    std::vector<Channel> pixels;  // width * height * kChannels

    Image() = default;
    // Every pixel set to (r, g, b, a).
    Image(int w, int h, Channel r = 0, Channel g = 0, Channel b = 0, Channel a = kOpaque)
        : width(w), height(h), pixels(static_cast<std::size_t>(w) * h * kChannels) {
        SYLVA_CHECK(w >= 0 && h >= 0);
        for (std::size_t i = 0; i < pixels.size(); i += kChannels) {
            pixels[i] = r;
            pixels[i + 1] = g;
            pixels[i + 2] = b;
            pixels[i + 3] = a;
        }
    }
    // The kChannels values of pixel (x, y).
    Channel* at(int x, int y) {
        SYLVA_CHECK(x >= 0 && x < width && y >= 0 && y < height);
        return pixels.data() + (static_cast<std::size_t>(y) * width + x) * kChannels;
    }
    const Channel* at(int x, int y) const { return const_cast<Image*>(this)->at(x, y); }
};

using RgbaImage = Image<std::uint8_t>;  // sRGB-encoded 8-bit colour, linear alpha
using LinearImage = Image<float>;       // linear radiance × exposure, alpha in [0, 1]

// Copies the `width` × `height` block of `source` whose top-left pixel is (sourceX,
// sourceY) to `target` at (targetX, targetY). The block must lie inside both images.
template <typename Channel>
void copyPixels(const Image<Channel>& source, int sourceX, int sourceY, int width, int height,
                Image<Channel>& target, int targetX, int targetY) {
    SYLVA_CHECK(width >= 0 && height >= 0);
    if (width == 0 || height == 0) {
        return;
    }
    SYLVA_CHECK(sourceX + width <= source.width && targetX + width <= target.width);
    for (int row = 0; row < height; ++row) {
        // at() checks the first pixel of each row; the asserts above its last.
        std::copy_n(source.at(sourceX, sourceY + row),
                    static_cast<std::size_t>(width) * Image<Channel>::kChannels,
                    target.at(targetX, targetY + row));
    }
}

// Sets every pixel of the rectangle [x0, x1) × [y0, y1) to `rgba`, clipped to the image
// (so drawings may run over its edges).
template <typename Channel>
void fillPixels(Image<Channel>& image, int x0, int y0, int x1, int y1,
                const std::array<Channel, 4>& rgba) {
    for (int y = std::max(y0, 0); y < std::min(y1, image.height); ++y) {
        for (int x = std::max(x0, 0); x < std::min(x1, image.width); ++x) {
            std::copy(rgba.begin(), rgba.end(), image.at(x, y));
        }
    }
}

}  // namespace sylva
