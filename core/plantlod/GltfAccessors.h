// GltfAccessors: glTF 2.0 accessor data as plain arrays (glTF 2.0 §3.6.2): vertex
// attributes as floats (normalized integers scaled to [0, 1] or [−1, 1]) and indices as
// u32, with strides, offsets and buffer bounds checked. Sparse accessors are not
// supported. Errors start with the file path and name the accessor.
#pragma once

#include <cstdint>
#include <filesystem>
#include <vector>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#include <tiny_gltf.h>
#pragma GCC diagnostic pop

#include "sylva/core/base/Result.h"

namespace sylva::plantimport {

// Accessor `index` as `components` floats per element; an accessor without a buffer
// view is all zeros (by the specification).
Result<std::vector<float>> readGltfFloats(const std::filesystem::path& path,
                                          const tinygltf::Model& gltf, int index, int components);

// Accessor `index` as indices: unsigned scalars of 1, 2 or 4 bytes in a buffer view.
Result<std::vector<std::uint32_t>> readGltfIndices(const std::filesystem::path& path,
                                                   const tinygltf::Model& gltf, int index);

}  // namespace sylva::plantimport
