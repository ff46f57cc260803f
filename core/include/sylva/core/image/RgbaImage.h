// RgbaImage: an 8-bit RGBA picture as Sylva writes it: sRGB-encoded colour, linear
// alpha, rows top to bottom, 4 bytes per pixel. The unit of comparison images and
// contact sheets (CPU side; the renderer reads its framebuffer into one).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "sylva/core/base/Check.h"

namespace sylva {

struct RgbaImage {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> pixels;  // width * height * 4

    RgbaImage() = default;
    RgbaImage(int w, int h, std::uint8_t r = 0, std::uint8_t g = 0, std::uint8_t b = 0,
              std::uint8_t a = 255)
        : width(w), height(h), pixels(static_cast<std::size_t>(w) * h * 4) {
        SYLVA_CHECK(w >= 0 && h >= 0);
        for (std::size_t i = 0; i < pixels.size(); i += 4) {
            pixels[i] = r;
            pixels[i + 1] = g;
            pixels[i + 2] = b;
            pixels[i + 3] = a;
        }
    }
    std::uint8_t* at(int x, int y) {
        SYLVA_CHECK(x >= 0 && x < width && y >= 0 && y < height);
        return pixels.data() + (static_cast<std::size_t>(y) * width + x) * 4;
    }
    const std::uint8_t* at(int x, int y) const { return const_cast<RgbaImage*>(this)->at(x, y); }
};

}  // namespace sylva
