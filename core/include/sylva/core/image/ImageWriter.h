// ImageWriter: writes 8-bit sRGB RGBA images (PNG, or whatever OpenImageIO infers
// from the extension) atomically: the pixels go to a temporary file in the target
// folder, which is renamed over the target only when complete. A failed or
// interrupted write never leaves a partial image under the final name.
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

#include "sylva/core/base/Result.h"

namespace sylva {

class ImageWriter {
public:
    // `pixels`: width * height * 4 bytes, rows top to bottom, sRGB-encoded RGBA.
    // Creates missing parent folders. Errors name the path and the reason.
    static Status writeRgba8(const std::filesystem::path& path, int width, int height,
                             const std::vector<std::uint8_t>& pixels);
    // Reads any image OpenImageIO can read into 8-bit RGBA (alpha 255 if absent).
    static Result<std::vector<std::uint8_t>> readRgba8(const std::filesystem::path& path,
                                                       int& width, int& height);
};

}  // namespace sylva
