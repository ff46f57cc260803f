#include "sylva/core/image/GltfImageDecoder.h"

#include <algorithm>
#include <array>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#include <tiny_gltf.h>
#pragma GCC diagnostic pop

namespace sylva {

Result<RgbaImage> decodeGltfImage(const std::filesystem::path& path, const tinygltf::Image& image,
                                  int index) {
    if (image.width <= 0 || image.height <= 0 || image.image.empty()) {
        return Error{path.string() + ": image " + std::to_string(index) + " could not be decoded"};
    }
    const int components = image.component;
    const int bytes = image.bits == 16 ? 2 : 1;
    const std::size_t pixels = std::size_t(image.width) * std::size_t(image.height);
    if (components < 1 || components > 4 ||
        image.image.size() < pixels * std::size_t(components * bytes)) {
        return Error{path.string() + ": image " + std::to_string(index) +
                     " has an unsupported pixel layout"};
    }
    RgbaImage texture(image.width, image.height);
    for (std::size_t i = 0; i < pixels; ++i) {
        std::array<std::uint8_t, 4> value = {0, 0, 0, 255};
        for (int c = 0; c < components; ++c) {
            // 16-bit samples are little-endian in tinygltf's decoded data: keep the high byte.
            value[std::size_t(c)] =
                image.image[(i * std::size_t(components) + std::size_t(c)) * std::size_t(bytes) +
                            std::size_t(bytes - 1)];
        }
        if (components == 1 || components == 2) {
            // Grey (+ alpha).
            value = {value[0], value[0], value[0], components == 2 ? value[1] : std::uint8_t(255)};
        }
        std::copy(value.begin(), value.end(), texture.pixels.begin() + std::ptrdiff_t(i * 4));
    }
    return texture;
}

}  // namespace sylva
