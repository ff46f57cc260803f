// ImageWriter: writes images through OpenImageIO atomically: the pixels go to a
// temporary file in the target folder, which is renamed over the target only when
// complete. A failed or interrupted write never leaves a partial image under the final
// name. Two kinds: 8-bit sRGB RGBA (PNG, or whatever OIIO infers from the extension)
// and linear float RGBA (OpenEXR, stored as half floats).
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

#include "sylva/core/base/Result.h"
#include "sylva/core/image/Image.h"
#include "sylva/core/image/ImageMetadata.h"

namespace sylva {

class ImageWriter {
public:
    // `pixels`: width * height * 4 bytes, rows top to bottom, sRGB-encoded RGBA.
    // `metadata` becomes text attributes (PNG tEXt chunks). Creates missing parent
    // folders. Errors name the path and the reason.
    static Status writeRgba8(const std::filesystem::path& path, int width, int height,
                             const std::vector<std::uint8_t>& pixels,
                             const ImageMetadata& metadata = {});
    // Linear radiance as half-float RGBA (the path should end in .exr; ZIP compression,
    // colour space "Linear", i.e. linear Rec.709/sRGB primaries), with `metadata` as
    // string attributes. Values beyond the half range (65504) are clamped to it.
    static Status writeLinear(const std::filesystem::path& path, const LinearImage& image,
                              const ImageMetadata& metadata = {});
    // True when `path` names an EXR file (extension .exr, any case).
    static bool isExr(const std::filesystem::path& path);

    // Reads any image OpenImageIO can read into 8-bit RGBA (alpha 255 if absent).
    static Result<std::vector<std::uint8_t>> readRgba8(const std::filesystem::path& path,
                                                       int& width, int& height);
    // Reads any image as float RGBA without conversion of the values (alpha 1 if absent).
    static Result<LinearImage> readLinear(const std::filesystem::path& path);
    // The string attributes of an image file (those named in `names` that it has).
    static Result<ImageMetadata> readMetadata(const std::filesystem::path& path,
                                              const std::vector<std::string>& names);
};

}  // namespace sylva
