// decodeGltfImage: one image of a glTF file, as tinygltf decoded it (stb_image: PNG,
// JPEG), into 8-bit RGBA — the one decoder of the plant importer (GltfPlantReader) and the
// model importer of the `objects` source (ModelImporter).
//
// Pixels: rows top to bottom as stored in the file (glTF's texture coordinate v = 0 is the
// first row); colour channels as encoded (sRGB for a base colour texture), alpha linear.
// Grey images are spread to RGB, grey + alpha keeps its alpha, a missing alpha is 255, and
// 16-bit samples keep their high byte.
//
// Fails with "<path>: image <index> could not be decoded" (no pixels: a missing or corrupt
// image file) or "... has an unsupported pixel layout" (more than four channels, or fewer
// bytes than the stated size).
#pragma once

#include <filesystem>

#include "sylva/core/base/Result.h"
#include "sylva/core/image/Image.h"

namespace tinygltf {
struct Image;
}

namespace sylva {

Result<RgbaImage> decodeGltfImage(const std::filesystem::path& path, const tinygltf::Image& image,
                                  int index);

}  // namespace sylva
