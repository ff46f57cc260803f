#include "GltfAccessors.h"

#include <algorithm>
#include <cstring>
#include <string>
#include <utility>

namespace sylva::plantimport {

namespace {

// The accessor, if it exists and is not sparse.
Result<const tinygltf::Accessor*> findAccessor(const std::string& where,
                                               const tinygltf::Model& gltf, int index) {
    if (index < 0 || std::size_t(index) >= gltf.accessors.size()) {
        return Error{where + ": does not exist"};
    }
    const tinygltf::Accessor& accessor = gltf.accessors[std::size_t(index)];
    if (accessor.sparse.isSparse) {
        return Error{where + ": unsupported glTF feature: sparse accessors"};
    }
    return &accessor;
}

// Whether `count` elements of `elementSize` bytes at `stride` fit the view and its buffer.
// Written without overflow: offsets, counts and strides come from the file.
bool fitsBuffer(const tinygltf::Accessor& accessor, const tinygltf::BufferView& view,
                const tinygltf::Buffer& buffer, std::size_t stride, std::size_t elementSize) {
    if (view.byteLength > buffer.data.size() ||
        view.byteOffset > buffer.data.size() - view.byteLength)
        return false;
    if (accessor.count == 0)
        return true;
    if (accessor.byteOffset > view.byteLength ||
        elementSize > view.byteLength - accessor.byteOffset)
        return false;
    const std::size_t room = view.byteLength - accessor.byteOffset - elementSize;
    return stride == 0 || accessor.count - 1 <= room / stride;
}

// The buffer view of `accessor` and its buffer, when both exist.
Result<std::pair<const tinygltf::BufferView*, const tinygltf::Buffer*>> viewOf(
    const std::string& where, const tinygltf::Model& gltf, const tinygltf::Accessor& accessor) {
    if (accessor.bufferView < 0 || std::size_t(accessor.bufferView) >= gltf.bufferViews.size())
        return Error{where + ": refers to a missing buffer view " +
                     std::to_string(accessor.bufferView)};
    const tinygltf::BufferView& view = gltf.bufferViews[std::size_t(accessor.bufferView)];
    if (view.buffer < 0 || std::size_t(view.buffer) >= gltf.buffers.size())
        return Error{where + ": its buffer view refers to a missing buffer " +
                     std::to_string(view.buffer)};
    return std::pair{&view, &gltf.buffers[std::size_t(view.buffer)]};
}

// One component at `p` as a float; false for a component type not allowed here.
bool readComponent(const unsigned char* p, int componentType, bool normalized, float& value) {
    switch (componentType) {
        case TINYGLTF_COMPONENT_TYPE_FLOAT:
            std::memcpy(&value, p, 4);
            return true;
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
            value = float(*p) / (normalized ? 255.0f : 1.0f);
            return true;
        case TINYGLTF_COMPONENT_TYPE_BYTE: {
            const float raw = float(static_cast<std::int8_t>(*p));
            value = normalized ? std::max(raw / 127.0f, -1.0f) : raw;
            return true;
        }
        case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
            std::uint16_t raw;
            std::memcpy(&raw, p, 2);
            value = float(raw) / (normalized ? 65535.0f : 1.0f);
            return true;
        }
        case TINYGLTF_COMPONENT_TYPE_SHORT: {
            std::int16_t raw;
            std::memcpy(&raw, p, 2);
            value = normalized ? std::max(float(raw) / 32767.0f, -1.0f) : float(raw);
            return true;
        }
        default:
            return false;
    }
}

}  // namespace

Result<std::vector<float>> readGltfFloats(const std::filesystem::path& path,
                                          const tinygltf::Model& gltf, int index, int components) {
    const std::string where = path.string() + ": accessor " + std::to_string(index);
    Result<const tinygltf::Accessor*> found = findAccessor(where, gltf, index);
    if (!found) {
        return found.error();
    }
    const tinygltf::Accessor& accessor = **found;
    const int actual = tinygltf::GetNumComponentsInType(std::uint32_t(accessor.type));
    if (actual != components) {
        return Error{where + ": has " + std::to_string(actual) + " components, expected " +
                     std::to_string(components)};
    }
    std::vector<float> values(accessor.count * std::size_t(components), 0.0f);
    if (accessor.bufferView < 0) {
        return values;  // all zeros by the specification
    }
    auto viewAndBuffer = viewOf(where, gltf, accessor);
    if (!viewAndBuffer) {
        return viewAndBuffer.error();
    }
    const tinygltf::BufferView& view = *viewAndBuffer->first;
    const tinygltf::Buffer& buffer = *viewAndBuffer->second;
    const int componentSize =
        tinygltf::GetComponentSizeInBytes(std::uint32_t(accessor.componentType));
    if (componentSize <= 0) {
        return Error{where + ": unknown component type " + std::to_string(accessor.componentType)};
    }
    const std::size_t elementSize = std::size_t(componentSize * components);
    const std::size_t stride = view.byteStride > 0 ? view.byteStride : elementSize;
    if (!fitsBuffer(accessor, view, buffer, stride, elementSize)) {
        return Error{where + ": reaches past the end of its buffer"};
    }
    const std::size_t begin = view.byteOffset + accessor.byteOffset;
    for (std::size_t i = 0; i < accessor.count; ++i) {
        const unsigned char* element = buffer.data.data() + begin + stride * i;
        for (int c = 0; c < components; ++c) {
            float& value = values[i * std::size_t(components) + std::size_t(c)];
            if (!readComponent(element + c * componentSize, accessor.componentType,
                               accessor.normalized, value)) {
                return Error{where + ": component type " + std::to_string(accessor.componentType) +
                             " is not allowed here"};
            }
        }
    }
    return values;
}

Result<std::vector<std::uint32_t>> readGltfIndices(const std::filesystem::path& path,
                                                   const tinygltf::Model& gltf, int index) {
    const std::string where = path.string() + ": accessor " + std::to_string(index);
    Result<const tinygltf::Accessor*> found = findAccessor(where, gltf, index);
    if (!found) {
        return found.error();
    }
    const tinygltf::Accessor& accessor = **found;
    if (accessor.bufferView < 0 || accessor.type != TINYGLTF_TYPE_SCALAR) {
        return Error{where + ": indices must be scalars in a buffer view"};
    }
    auto viewAndBuffer = viewOf(where, gltf, accessor);
    if (!viewAndBuffer) {
        return viewAndBuffer.error();
    }
    const tinygltf::BufferView& view = *viewAndBuffer->first;
    const tinygltf::Buffer& buffer = *viewAndBuffer->second;
    const int size = tinygltf::GetComponentSizeInBytes(std::uint32_t(accessor.componentType));
    if (accessor.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
        accessor.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        accessor.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) {
        return Error{where + ": indices must be unsigned integers"};
    }
    const std::size_t stride = view.byteStride > 0 ? view.byteStride : std::size_t(size);
    if (!fitsBuffer(accessor, view, buffer, stride, std::size_t(size))) {
        return Error{where + ": reaches past the end of its buffer"};
    }
    const std::size_t begin = view.byteOffset + accessor.byteOffset;
    std::vector<std::uint32_t> indices(accessor.count);
    for (std::size_t i = 0; i < accessor.count; ++i) {
        const unsigned char* p = buffer.data.data() + begin + stride * i;
        if (size == 1) {
            indices[i] = *p;
        } else if (size == 2) {
            std::uint16_t raw;
            std::memcpy(&raw, p, 2);
            indices[i] = raw;
        } else {
            std::memcpy(&indices[i], p, 4);
        }
    }
    return indices;
}

}  // namespace sylva::plantimport
