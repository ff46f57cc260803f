// LinearImage: a floating-point RGBA picture in linear light, as Sylva writes EXR files:
// RGB = scene radiance × exposure (the renderer's value before tone mapping; no upper
// bound), alpha linear in [0, 1], rows top to bottom, 4 floats per pixel.
#pragma once

#include <cstddef>
#include <vector>

#include "sylva/core/base/Check.h"

namespace sylva {

struct LinearImage {
    int width = 0;
    int height = 0;
    std::vector<float> pixels;  // width * height * 4

    LinearImage() = default;
    LinearImage(int w, int h, float r = 0, float g = 0, float b = 0, float a = 1)
        : width(w), height(h), pixels(static_cast<std::size_t>(w) * h * 4) {
        SYLVA_CHECK(w >= 0 && h >= 0);
        for (std::size_t i = 0; i < pixels.size(); i += 4) {
            pixels[i] = r;
            pixels[i + 1] = g;
            pixels[i + 2] = b;
            pixels[i + 3] = a;
        }
    }
    float* at(int x, int y) {
        SYLVA_CHECK(x >= 0 && x < width && y >= 0 && y < height);
        return pixels.data() + (static_cast<std::size_t>(y) * width + x) * 4;
    }
    const float* at(int x, int y) const { return const_cast<LinearImage*>(this)->at(x, y); }
};

}  // namespace sylva
