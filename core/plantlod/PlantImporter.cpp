// Plant import (seed 001 §3.3): glTF through tinygltf, OBJ through our own reader, the
// leaf/branch split by sidecar, alpha and names, and the skeleton from the file or
// reconstructed (SkeletonReconstructor).
#include "sylva/core/plantlod/PlantImporter.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <numeric>
#include <optional>
#include <sstream>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <nlohmann/json.hpp>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#include <tiny_gltf.h>
#pragma GCC diagnostic pop

#include "sylva/core/image/ImageWriter.h"
#include "sylva/core/plantlod/SkeletonReconstructor.h"

namespace sylva {

namespace {

using Json = nlohmann::json;

// File frame (+Y up) to model frame (+Z up).
glm::vec3 toModel(const glm::vec3& v) {
    return {v.x, -v.z, v.y};
}

std::string lowercase(std::string text) {
    for (char& c : text) {
        c = char(std::tolower(static_cast<unsigned char>(c)));
    }
    return text;
}

bool hasLeafName(const std::string& name) {
    static const std::array<const char*, 9> words = {
        "leaf", "leaves", "needle", "foliage", "frond", "blatt", "laub", "nadel", "feuille"};
    const std::string lower = lowercase(name);
    return std::any_of(words.begin(), words.end(),
                       [&](const char* word) { return lower.find(word) != std::string::npos; });
}

bool textureHasAlpha(const PlantTexture& texture) {
    for (std::size_t i = 3; i < texture.rgba.size(); i += 4) {
        if (texture.rgba[i] < 128) {
            return true;
        }
    }
    return false;
}

Result<std::string> readFile(const std::filesystem::path& path) {
    std::error_code error;
    if (!std::filesystem::is_regular_file(path, error)) {
        return Error{path.string() + ": file not found"};
    }
    std::ifstream in(path, std::ios::binary);
    std::ostringstream bytes;
    bytes << in.rdbuf();
    if (!in && !in.eof()) {
        return Error{path.string() + ": cannot read the file"};
    }
    return bytes.str();
}

// The sidecar: {"parts": {"name": "leaf" | "branch", ...}}.
Result<std::map<std::string, PlantPart>> readSidecar(const std::filesystem::path& model) {
    const std::filesystem::path path =
        model.parent_path() / (model.stem().string() + ".plant.json");
    std::map<std::string, PlantPart> parts;
    std::error_code error;
    if (!std::filesystem::exists(path, error)) {
        return parts;
    }
    Result<std::string> text = readFile(path);
    if (!text) {
        return text.error();
    }
    Json json;
    try {
        json = Json::parse(*text);
    } catch (const Json::parse_error& e) {
        return Error{path.string() + ": invalid JSON at byte " + std::to_string(e.byte)};
    }
    if (!json.is_object() || !json.contains("parts") || !json["parts"].is_object()) {
        return Error{path.string() + ": expected an object with a \"parts\" object"};
    }
    for (const auto& [name, value] : json["parts"].items()) {
        if (value == "leaf") {
            parts[name] = PlantPart::Leaf;
        } else if (value == "branch") {
            parts[name] = PlantPart::Branch;
        } else {
            return Error{path.string() + ": parts." + name + ": must be \"leaf\" or \"branch\""};
        }
    }
    return parts;
}

// One primitive before classification: the names that may decide its part.
struct NamedMesh {
    PlantMesh mesh;
    std::string materialName;
    std::string meshName;
    std::string nodeName;
};

PlantPart classify(const NamedMesh& named, const std::vector<PlantMaterial>& materials,
                   const std::map<std::string, PlantPart>& sidecar) {
    for (const std::string* name : {&named.materialName, &named.meshName, &named.nodeName}) {
        if (auto it = sidecar.find(*name); !name->empty() && it != sidecar.end()) {
            return it->second;
        }
    }
    if (named.mesh.material >= 0) {
        const PlantMaterial& material = materials[std::size_t(named.mesh.material)];
        if (material.alphaMasked || material.baseColor.a < 1.0f ||
            textureHasAlpha(material.baseColorTexture)) {
            return PlantPart::Leaf;
        }
    }
    if (hasLeafName(named.materialName) || hasLeafName(named.meshName) ||
        hasLeafName(named.nodeName)) {
        return PlantPart::Leaf;
    }
    return PlantPart::Branch;
}

void computeMissingNormals(PlantMesh& mesh) {
    if (mesh.normals.size() == mesh.positions.size()) {
        return;
    }
    mesh.normals.assign(mesh.positions.size(), glm::vec3(0.0f));
    for (std::size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
        const glm::vec3& a = mesh.positions[mesh.indices[i]];
        const glm::vec3& b = mesh.positions[mesh.indices[i + 1]];
        const glm::vec3& c = mesh.positions[mesh.indices[i + 2]];
        const glm::vec3 n = glm::cross(b - a, c - a);
        for (std::size_t k = 0; k < 3; ++k) {
            mesh.normals[mesh.indices[i + k]] += n;
        }
    }
    for (glm::vec3& n : mesh.normals) {
        const float length = glm::length(n);
        n = length > 0.0f ? n / length : glm::vec3(0.0f, 0.0f, 1.0f);
    }
}

// Finishes a model: classification, skeleton, the leaves-and-branches requirement.
Result<PlantModel> finish(const std::filesystem::path& path, std::vector<NamedMesh> named,
                          std::vector<PlantMaterial> materials,
                          std::vector<SkeletonSegment> skeleton,
                          const PlantImportOptions& options) {
    Result<std::map<std::string, PlantPart>> sidecar = readSidecar(path);
    if (!sidecar) {
        return sidecar.error();
    }
    PlantModel model;
    model.name = path.stem().string();
    for (NamedMesh& entry : named) {
        entry.mesh.part = classify(entry, materials, *sidecar);
        if (entry.mesh.part == PlantPart::Leaf && entry.mesh.material >= 0) {
            PlantMaterial& material = materials[std::size_t(entry.mesh.material)];
            // A leaf material with alpha anywhere is alpha-tested (seed 001 §3.3.1 discards
            // samples with alpha < 0.5).
            if (textureHasAlpha(material.baseColorTexture) || material.baseColor.a < 1.0f) {
                material.alphaMasked = true;
            }
        }
        computeMissingNormals(entry.mesh);
        if (!entry.mesh.indices.empty()) {
            model.meshes.push_back(std::move(entry.mesh));
        }
    }
    model.materials = std::move(materials);
    if (options.requireLeavesAndBranches) {
        if (model.triangleCount(PlantPart::Leaf) == 0) {
            return Error{path.string() +
                         ": the model has no leaves (no alpha-masked or alpha-textured material, "
                         "no leaf-like "
                         "name, no sidecar entry)"};
        }
        if (model.triangleCount(PlantPart::Branch) == 0) {
            return Error{path.string() +
                         ": the model has no branches (every mesh was classified as leaves)"};
        }
    }
    model.skeleton =
        skeleton.empty() ? SkeletonReconstructor::reconstruct(model.meshes) : std::move(skeleton);
    return model;
}

// ---------------------------------------------------------------------------- glTF

Result<std::vector<SkeletonSegment>> readSkeleton(const std::filesystem::path& path,
                                                  const Json& list, const std::string& where) {
    std::vector<SkeletonSegment> skeleton;
    if (!list.is_array()) {
        return Error{path.string() + ": " + where + ": must be an array of segments"};
    }
    auto vector = [](const Json& value, glm::vec3& out) {
        if (!value.is_array() || value.size() != 3) {
            return false;
        }
        for (std::size_t i = 0; i < 3; ++i) {
            if (!value[i].is_number()) {
                return false;
            }
            out[int(i)] = value[i].get<float>();
        }
        out = toModel(out);
        return true;
    };
    for (std::size_t i = 0; i < list.size(); ++i) {
        const Json& entry = list[i];
        const std::string at = where + "[" + std::to_string(i) + "]";
        SkeletonSegment segment;
        if (!entry.is_object() || !vector(entry.value("start", Json()), segment.start) ||
            !vector(entry.value("end", Json()), segment.end)) {
            return Error{path.string() + ": " + at + ": needs start and end as [x, y, z]"};
        }
        const Json startRadius = entry.value("startRadius", Json());
        const Json endRadius = entry.value("endRadius", Json());
        if (!startRadius.is_number() || !endRadius.is_number() || startRadius.get<double>() < 0.0 ||
            endRadius.get<double>() < 0.0) {
            return Error{path.string() + ": " + at +
                         ": startRadius and endRadius must be numbers >= 0"};
        }
        segment.startRadius = startRadius.get<float>();
        segment.endRadius = endRadius.get<float>();
        const Json parent = entry.value("parent", Json(-1));
        if (!parent.is_number_integer() || parent.get<long long>() < -1 ||
            parent.get<long long>() >= (long long)(list.size()) ||
            parent.get<long long>() == (long long)(i)) {
            return Error{path.string() + ": " + at +
                         ".parent: must be -1 or the index of another segment"};
        }
        segment.parent = parent.get<int>();
        skeleton.push_back(segment);
    }
    // Parents must form a forest: walking up from any segment ends at a root.
    for (std::size_t i = 0; i < skeleton.size(); ++i) {
        int current = int(i);
        for (std::size_t steps = 0; current >= 0; ++steps) {
            if (steps > skeleton.size()) {
                return Error{path.string() + ": " + where +
                             ": the parents form a cycle through segment " + std::to_string(i)};
            }
            current = skeleton[std::size_t(current)].parent;
        }
    }
    return skeleton;
}

const char* modeName(int mode) {
    switch (mode) {
        case TINYGLTF_MODE_POINTS:
            return "POINTS";
        case TINYGLTF_MODE_LINE:
            return "LINES";
        case TINYGLTF_MODE_LINE_LOOP:
            return "LINE_LOOP";
        case TINYGLTF_MODE_LINE_STRIP:
            return "LINE_STRIP";
        default:
            return "unknown";
    }
}

// Reads an accessor as `components` floats per element (normalized integers scaled).
Result<std::vector<float>> readFloats(const std::filesystem::path& path,
                                      const tinygltf::Model& gltf, int index, int components) {
    const std::string where = path.string() + ": accessor " + std::to_string(index);
    if (index < 0 || std::size_t(index) >= gltf.accessors.size()) {
        return Error{where + ": does not exist"};
    }
    const tinygltf::Accessor& accessor = gltf.accessors[std::size_t(index)];
    if (accessor.sparse.isSparse) {
        return Error{where + ": unsupported glTF feature: sparse accessors"};
    }
    if (tinygltf::GetNumComponentsInType(std::uint32_t(accessor.type)) != components) {
        return Error{
            where + ": has " +
            std::to_string(tinygltf::GetNumComponentsInType(std::uint32_t(accessor.type))) +
            " components, expected " + std::to_string(components)};
    }
    std::vector<float> values(accessor.count * std::size_t(components), 0.0f);
    if (accessor.bufferView < 0) {
        return values;  // all zeros by the specification
    }
    const tinygltf::BufferView& view = gltf.bufferViews[std::size_t(accessor.bufferView)];
    const tinygltf::Buffer& buffer = gltf.buffers[std::size_t(view.buffer)];
    const int componentSize =
        tinygltf::GetComponentSizeInBytes(std::uint32_t(accessor.componentType));
    if (componentSize <= 0) {
        return Error{where + ": unknown component type " + std::to_string(accessor.componentType)};
    }
    const std::size_t elementSize = std::size_t(componentSize * components);
    const std::size_t stride = view.byteStride > 0 ? view.byteStride : elementSize;
    const std::size_t begin = view.byteOffset + accessor.byteOffset;
    if (accessor.count > 0 &&
        (begin + stride * (accessor.count - 1) + elementSize > view.byteOffset + view.byteLength ||
         view.byteOffset + view.byteLength > buffer.data.size())) {
        return Error{where + ": reaches past the end of its buffer"};
    }
    for (std::size_t i = 0; i < accessor.count; ++i) {
        const unsigned char* element = buffer.data.data() + begin + stride * i;
        for (int c = 0; c < components; ++c) {
            const unsigned char* p = element + c * componentSize;
            float value = 0.0f;
            switch (accessor.componentType) {
                case TINYGLTF_COMPONENT_TYPE_FLOAT:
                    std::memcpy(&value, p, 4);
                    break;
                case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
                    value = float(*p) / (accessor.normalized ? 255.0f : 1.0f);
                    break;
                case TINYGLTF_COMPONENT_TYPE_BYTE: {
                    const float raw = float(static_cast<std::int8_t>(*p));
                    value = accessor.normalized ? std::max(raw / 127.0f, -1.0f) : raw;
                    break;
                }
                case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
                    std::uint16_t raw;
                    std::memcpy(&raw, p, 2);
                    value = float(raw) / (accessor.normalized ? 65535.0f : 1.0f);
                    break;
                }
                case TINYGLTF_COMPONENT_TYPE_SHORT: {
                    std::int16_t raw;
                    std::memcpy(&raw, p, 2);
                    value =
                        accessor.normalized ? std::max(float(raw) / 32767.0f, -1.0f) : float(raw);
                    break;
                }
                default:
                    return Error{where + ": component type " +
                                 std::to_string(accessor.componentType) + " is not allowed here"};
            }
            values[i * std::size_t(components) + std::size_t(c)] = value;
        }
    }
    return values;
}

Result<std::vector<std::uint32_t>> readIndices(const std::filesystem::path& path,
                                               const tinygltf::Model& gltf, int index) {
    const std::string where = path.string() + ": accessor " + std::to_string(index);
    if (index < 0 || std::size_t(index) >= gltf.accessors.size()) {
        return Error{where + ": does not exist"};
    }
    const tinygltf::Accessor& accessor = gltf.accessors[std::size_t(index)];
    if (accessor.sparse.isSparse) {
        return Error{where + ": unsupported glTF feature: sparse accessors"};
    }
    if (accessor.bufferView < 0 || accessor.type != TINYGLTF_TYPE_SCALAR) {
        return Error{where + ": indices must be scalars in a buffer view"};
    }
    const tinygltf::BufferView& view = gltf.bufferViews[std::size_t(accessor.bufferView)];
    const tinygltf::Buffer& buffer = gltf.buffers[std::size_t(view.buffer)];
    const int size = tinygltf::GetComponentSizeInBytes(std::uint32_t(accessor.componentType));
    if (accessor.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
        accessor.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        accessor.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) {
        return Error{where + ": indices must be unsigned integers"};
    }
    const std::size_t stride = view.byteStride > 0 ? view.byteStride : std::size_t(size);
    const std::size_t begin = view.byteOffset + accessor.byteOffset;
    if (accessor.count > 0 && (begin + stride * (accessor.count - 1) + std::size_t(size) >
                                   view.byteOffset + view.byteLength ||
                               view.byteOffset + view.byteLength > buffer.data.size())) {
        return Error{where + ": reaches past the end of its buffer"};
    }
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

glm::dmat4 nodeMatrix(const tinygltf::Node& node) {
    if (node.matrix.size() == 16) {
        glm::dmat4 matrix;
        for (int i = 0; i < 16; ++i) {
            matrix[i / 4][i % 4] = node.matrix[std::size_t(i)];
        }
        return matrix;
    }
    glm::dmat4 matrix(1.0);
    if (node.translation.size() == 3) {
        matrix = glm::translate(
            matrix, glm::dvec3(node.translation[0], node.translation[1], node.translation[2]));
    }
    if (node.rotation.size() == 4) {
        const glm::dquat rotation(node.rotation[3], node.rotation[0], node.rotation[1],
                                  node.rotation[2]);
        matrix = matrix * glm::mat4_cast(glm::normalize(rotation));
    }
    if (node.scale.size() == 3) {
        matrix = glm::scale(matrix, glm::dvec3(node.scale[0], node.scale[1], node.scale[2]));
    }
    return matrix;
}

Result<PlantTexture> decodeImage(const std::filesystem::path& path, const tinygltf::Image& image,
                                 int index) {
    PlantTexture texture;
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
    texture.width = image.width;
    texture.height = image.height;
    texture.rgba.resize(pixels * 4);
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
        std::copy(value.begin(), value.end(), texture.rgba.begin() + std::ptrdiff_t(i * 4));
    }
    return texture;
}

// GLB container checks with our own messages (tinygltf's are not stable text).
Result<std::string> glbJson(const std::filesystem::path& path, const std::string& bytes) {
    auto read32 = [&](std::size_t offset) {
        std::uint32_t value;
        std::memcpy(&value, bytes.data() + offset, 4);
        return value;
    };
    if (bytes.size() < 20) {
        return Error{path.string() + ": truncated GLB: " + std::to_string(bytes.size()) +
                     " bytes, less than the 20-byte header"};
    }
    if (read32(0) != 0x46546C67u) {
        return Error{path.string() + ": not a GLB file (bad magic)"};
    }
    if (read32(4) != 2) {
        return Error{path.string() + ": unsupported GLB version " + std::to_string(read32(4)) +
                     " (only 2)"};
    }
    if (read32(8) > bytes.size()) {
        return Error{path.string() + ": truncated GLB: the header says " +
                     std::to_string(read32(8)) + " bytes, the file has " +
                     std::to_string(bytes.size())};
    }
    const std::uint32_t jsonLength = read32(12);
    if (read32(16) != 0x4E4F534Au || 20 + std::size_t(jsonLength) > bytes.size()) {
        return Error{path.string() + ": corrupt GLB: the first chunk is not a complete JSON chunk"};
    }
    return bytes.substr(20, jsonLength);
}

Result<PlantModel> importGltf(const std::filesystem::path& path,
                              const PlantImportOptions& options) {
    Result<std::string> bytes = readFile(path);
    if (!bytes) {
        return bytes.error();
    }
    const bool binary = bytes->size() >= 4 && bytes->compare(0, 4, "glTF") == 0;
    if (path.extension() == ".glb" && !binary) {
        if (bytes->size() < 4) {
            return Error{path.string() + ": truncated GLB: " + std::to_string(bytes->size()) +
                         " bytes, less than the 20-byte header"};
        }
        return Error{path.string() + ": not a GLB file (bad magic)"};
    }
    std::string jsonText = *bytes;
    if (binary) {
        Result<std::string> chunk = glbJson(path, *bytes);
        if (!chunk) {
            return chunk.error();
        }
        jsonText = *chunk;
    }
    Json json;
    try {
        json = Json::parse(jsonText);
    } catch (const Json::parse_error& e) {
        return Error{path.string() + ": corrupt glTF: invalid JSON at byte " +
                     std::to_string(e.byte)};
    }
    if (!json.is_object() || !json.contains("asset") || !json["asset"].is_object()) {
        return Error{path.string() + ": corrupt glTF: no \"asset\" object"};
    }
    const std::string version = json["asset"].value("version", "");
    if (version.rfind("2.", 0) != 0) {
        return Error{path.string() + ": unsupported glTF version '" + version + "' (only 2.x)"};
    }
    for (const Json& extension : json.value("extensionsRequired", Json::array())) {
        const std::string name = extension.is_string() ? extension.get<std::string>() : "?";
        if (name == "KHR_materials_unlit") {
            continue;
        }
        if (name == "KHR_draco_mesh_compression") {
            return Error{
                path.string() +
                ": unsupported glTF feature: Draco mesh compression (KHR_draco_mesh_compression)"};
        }
        return Error{path.string() + ": unsupported glTF feature: required extension " + name};
    }
    const std::filesystem::path folder = path.parent_path();
    for (const char* kind : {"buffers", "images"}) {
        const Json list = json.value(kind, Json::array());
        for (std::size_t i = 0; i < list.size(); ++i) {
            if (!list[i].is_object() || !list[i].contains("uri") || !list[i]["uri"].is_string()) {
                continue;
            }
            const std::string uri = list[i]["uri"].get<std::string>();
            std::error_code error;
            if (uri.rfind("data:", 0) != 0 && !std::filesystem::exists(folder / uri, error)) {
                return Error{path.string() + ": " +
                             std::string(kind).substr(0, std::string(kind).size() - 1) + " " +
                             std::to_string(i) + " refers to the missing file '" + uri + "'"};
            }
        }
    }

    tinygltf::Model gltf;
    tinygltf::TinyGLTF loader;
    std::string error;
    std::string warning;
    bool loaded;
    if (binary) {
        loaded = loader.LoadBinaryFromMemory(&gltf, &error, &warning,
                                             reinterpret_cast<const unsigned char*>(bytes->data()),
                                             unsigned(bytes->size()), folder.string());
    } else {
        loaded = loader.LoadASCIIFromString(&gltf, &error, &warning, bytes->data(),
                                            unsigned(bytes->size()), folder.string());
    }
    if (!loaded) {
        const std::string firstLine = error.substr(0, error.find('\n'));
        return Error{path.string() + ": corrupt glTF: " +
                     (firstLine.empty() ? "tinygltf could not load it" : firstLine)};
    }

    std::vector<PlantMaterial> materials;
    for (std::size_t i = 0; i < gltf.materials.size(); ++i) {
        const tinygltf::Material& source = gltf.materials[i];
        PlantMaterial material;
        material.name = source.name;
        const std::vector<double>& factor = source.pbrMetallicRoughness.baseColorFactor;
        if (factor.size() == 4) {
            material.baseColor =
                glm::vec4(float(factor[0]), float(factor[1]), float(factor[2]), float(factor[3]));
        }
        material.alphaMasked = source.alphaMode == "MASK" || source.alphaMode == "BLEND";
        material.alphaCutoff = source.alphaMode == "MASK" ? float(source.alphaCutoff) : 0.5f;
        const int textureIndex = source.pbrMetallicRoughness.baseColorTexture.index;
        if (textureIndex >= 0) {
            if (std::size_t(textureIndex) >= gltf.textures.size() ||
                gltf.textures[std::size_t(textureIndex)].source < 0 ||
                std::size_t(gltf.textures[std::size_t(textureIndex)].source) >=
                    gltf.images.size()) {
                return Error{path.string() + ": material " + std::to_string(i) +
                             " refers to a missing texture"};
            }
            const int imageIndex = gltf.textures[std::size_t(textureIndex)].source;
            Result<PlantTexture> texture =
                decodeImage(path, gltf.images[std::size_t(imageIndex)], imageIndex);
            if (!texture) {
                return texture.error();
            }
            material.baseColorTexture = std::move(*texture);
        }
        materials.push_back(std::move(material));
    }

    std::vector<NamedMesh> named;
    // Depth-first over the scene graph with accumulated transforms.
    std::vector<int> roots;
    const int sceneIndex = gltf.defaultScene >= 0 ? gltf.defaultScene : 0;
    if (std::size_t(sceneIndex) < gltf.scenes.size()) {
        roots = gltf.scenes[std::size_t(sceneIndex)].nodes;
    } else {
        std::vector<bool> isChild(gltf.nodes.size(), false);
        for (const tinygltf::Node& node : gltf.nodes) {
            for (int child : node.children) {
                if (child >= 0 && std::size_t(child) < isChild.size()) {
                    isChild[std::size_t(child)] = true;
                }
            }
        }
        for (std::size_t i = 0; i < gltf.nodes.size(); ++i) {
            if (!isChild[i]) {
                roots.push_back(int(i));
            }
        }
    }
    std::vector<std::pair<int, glm::dmat4>> stack;
    for (auto it = roots.rbegin(); it != roots.rend(); ++it) {
        stack.emplace_back(*it, glm::dmat4(1.0));
    }
    std::size_t visited = 0;
    while (!stack.empty()) {
        auto [nodeIndex, parentMatrix] = stack.back();
        stack.pop_back();
        if (nodeIndex < 0 || std::size_t(nodeIndex) >= gltf.nodes.size() ||
            ++visited > 4 * gltf.nodes.size() + 16) {
            return Error{path.string() + ": corrupt glTF: bad node hierarchy"};
        }
        const tinygltf::Node& node = gltf.nodes[std::size_t(nodeIndex)];
        const glm::dmat4 matrix = parentMatrix * nodeMatrix(node);
        for (auto child = node.children.rbegin(); child != node.children.rend(); ++child) {
            stack.emplace_back(*child, matrix);
        }
        if (node.mesh < 0) {
            continue;
        }
        if (std::size_t(node.mesh) >= gltf.meshes.size()) {
            return Error{path.string() + ": node " + std::to_string(nodeIndex) +
                         " refers to a missing mesh"};
        }
        const tinygltf::Mesh& mesh = gltf.meshes[std::size_t(node.mesh)];
        const glm::dmat3 normalMatrix = glm::transpose(glm::inverse(glm::dmat3(matrix)));
        const bool mirrored = glm::determinant(glm::dmat3(matrix)) < 0.0;
        for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
            const tinygltf::Primitive& primitive = mesh.primitives[p];
            const std::string where =
                path.string() + ": mesh '" + mesh.name + "' primitive " + std::to_string(p);
            if (primitive.mode != TINYGLTF_MODE_TRIANGLES &&
                primitive.mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
                primitive.mode != TINYGLTF_MODE_TRIANGLE_FAN && primitive.mode != -1) {
                return Error{where + ": unsupported glTF feature: " + modeName(primitive.mode) +
                             " primitives (only triangles)"};
            }
            auto positionIt = primitive.attributes.find("POSITION");
            if (positionIt == primitive.attributes.end()) {
                return Error{where + ": no POSITION attribute"};
            }
            Result<std::vector<float>> positions = readFloats(path, gltf, positionIt->second, 3);
            if (!positions) {
                return positions.error();
            }
            const std::size_t count = positions->size() / 3;
            NamedMesh entry;
            entry.meshName = mesh.name;
            entry.nodeName = node.name;
            entry.mesh.name = !mesh.name.empty() ? mesh.name : node.name;
            entry.mesh.material =
                primitive.material >= 0 && std::size_t(primitive.material) < materials.size()
                    ? primitive.material
                    : -1;
            if (entry.mesh.material >= 0) {
                entry.materialName = materials[std::size_t(entry.mesh.material)].name;
            }
            for (std::size_t i = 0; i < count; ++i) {
                const glm::dvec4 p4 =
                    matrix * glm::dvec4((*positions)[3 * i], (*positions)[3 * i + 1],
                                        (*positions)[3 * i + 2], 1.0);
                entry.mesh.positions.push_back(toModel(glm::vec3(p4)));
            }
            if (auto it = primitive.attributes.find("NORMAL"); it != primitive.attributes.end()) {
                Result<std::vector<float>> normals = readFloats(path, gltf, it->second, 3);
                if (!normals) {
                    return normals.error();
                }
                if (normals->size() != positions->size()) {
                    return Error{where + ": NORMAL and POSITION counts differ"};
                }
                for (std::size_t i = 0; i < count; ++i) {
                    glm::dvec3 n =
                        normalMatrix *
                        glm::dvec3((*normals)[3 * i], (*normals)[3 * i + 1], (*normals)[3 * i + 2]);
                    const double length = glm::length(n);
                    entry.mesh.normals.push_back(toModel(glm::vec3(length > 0.0 ? n / length : n)));
                }
            }
            if (auto it = primitive.attributes.find("TEXCOORD_0");
                it != primitive.attributes.end()) {
                Result<std::vector<float>> uvs = readFloats(path, gltf, it->second, 2);
                if (!uvs) {
                    return uvs.error();
                }
                if (uvs->size() / 2 != count) {
                    return Error{where + ": TEXCOORD_0 and POSITION counts differ"};
                }
                for (std::size_t i = 0; i < count; ++i) {
                    entry.mesh.uvs.emplace_back((*uvs)[2 * i], (*uvs)[2 * i + 1]);
                }
            }
            std::vector<std::uint32_t> indices;
            if (primitive.indices >= 0) {
                Result<std::vector<std::uint32_t>> read =
                    readIndices(path, gltf, primitive.indices);
                if (!read) {
                    return read.error();
                }
                indices = std::move(*read);
            } else {
                indices.resize(count);
                std::iota(indices.begin(), indices.end(), 0u);
            }
            for (std::uint32_t index : indices) {
                if (index >= count) {
                    return Error{where + ": index " + std::to_string(index) + " out of range (" +
                                 std::to_string(count) + " vertices)"};
                }
            }
            // Strips and fans become lists.
            std::vector<std::uint32_t> triangles;
            if (primitive.mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
                for (std::size_t i = 2; i < indices.size(); ++i) {
                    if (i % 2 == 0) {
                        triangles.insert(triangles.end(),
                                         {indices[i - 2], indices[i - 1], indices[i]});
                    } else {
                        triangles.insert(triangles.end(),
                                         {indices[i - 1], indices[i - 2], indices[i]});
                    }
                }
            } else if (primitive.mode == TINYGLTF_MODE_TRIANGLE_FAN) {
                for (std::size_t i = 2; i < indices.size(); ++i) {
                    triangles.insert(triangles.end(), {indices[0], indices[i - 1], indices[i]});
                }
            } else {
                if (indices.size() % 3 != 0) {
                    return Error{where + ": the index count " + std::to_string(indices.size()) +
                                 " is not a multiple of 3"};
                }
                triangles = std::move(indices);
            }
            if (mirrored) {
                for (std::size_t i = 0; i + 2 < triangles.size(); i += 3) {
                    std::swap(triangles[i + 1], triangles[i + 2]);
                }
            }
            entry.mesh.indices = std::move(triangles);
            named.push_back(std::move(entry));
        }
    }

    std::vector<SkeletonSegment> skeleton;
    if (options.useFileSkeleton) {
        const Json* list = nullptr;
        std::string where;
        if (json["asset"].contains("extras") && json["asset"]["extras"].is_object() &&
            json["asset"]["extras"].contains("sylva_skeleton")) {
            list = &json["asset"]["extras"]["sylva_skeleton"];
            where = "asset.extras.sylva_skeleton";
        } else if (!roots.empty() && json.contains("nodes") && json["nodes"].is_array() &&
                   std::size_t(roots.front()) < json["nodes"].size()) {
            const Json& root = json["nodes"][std::size_t(roots.front())];
            if (root.is_object() && root.contains("extras") && root["extras"].is_object() &&
                root["extras"].contains("sylva_skeleton")) {
                list = &root["extras"]["sylva_skeleton"];
                where = "nodes[" + std::to_string(roots.front()) + "].extras.sylva_skeleton";
            }
        }
        if (list != nullptr) {
            Result<std::vector<SkeletonSegment>> read = readSkeleton(path, *list, where);
            if (!read) {
                return read.error();
            }
            skeleton = std::move(*read);
        }
    }
    return finish(path, std::move(named), std::move(materials), std::move(skeleton), options);
}

// ---------------------------------------------------------------------------- OBJ

std::vector<std::string> splitWords(const std::string& line) {
    std::vector<std::string> words;
    std::istringstream stream(line);
    std::string word;
    while (stream >> word) {
        words.push_back(word);
    }
    return words;
}

bool parseFloat(const std::string& text, float& value) {
    const char* end = text.data() + text.size();
    auto [ptr, ec] = std::from_chars(text.data(), end, value);
    return ec == std::errc() && ptr == end;
}

// The rest of a line after its keyword (file names may contain spaces); options such
// as "-bm 1" before the file name are skipped.
std::string mapFileName(const std::vector<std::string>& words) {
    std::size_t i = 1;
    while (i + 1 < words.size() && words[i].size() > 1 && words[i][0] == '-') {
        i += words[i] == "-o" || words[i] == "-s" || words[i] == "-t" ? 4 : 2;
    }
    std::string name;
    for (; i < words.size(); ++i) {
        name += (name.empty() ? "" : " ") + words[i];
    }
    return name;
}

Result<PlantTexture> readTexture(const std::filesystem::path& library, int line,
                                 const std::filesystem::path& file) {
    std::error_code error;
    if (!std::filesystem::exists(file, error)) {
        return Error{library.string() + ":" + std::to_string(line) + ": texture '" + file.string() +
                     "' not found"};
    }
    PlantTexture texture;
    Result<std::vector<std::uint8_t>> pixels =
        ImageWriter::readRgba8(file, texture.width, texture.height);
    if (!pixels) {
        return Error{library.string() + ":" + std::to_string(line) + ": " + pixels.error().message};
    }
    texture.rgba = std::move(*pixels);
    return texture;
}

Status readMaterialLibrary(const std::filesystem::path& library,
                           std::vector<PlantMaterial>& materials,
                           std::map<std::string, int>& byName) {
    Result<std::string> text = readFile(library);
    if (!text) {
        return text.error();
    }
    std::istringstream lines(*text);
    std::string line;
    int number = 0;
    PlantMaterial* current = nullptr;
    std::optional<PlantTexture> alphaMap;
    auto finishMaterial = [&]() {
        if (current != nullptr && alphaMap) {
            // map_d: the opacity map, from its alpha channel when it has one, else its grey.
            PlantTexture& base = current->baseColorTexture;
            const bool ownAlpha = textureHasAlpha(*alphaMap);
            if (base.width == 0) {
                base.width = alphaMap->width;
                base.height = alphaMap->height;
                base.rgba.assign(alphaMap->rgba.size(), 255);
            }
            for (int y = 0; y < base.height; ++y) {
                for (int x = 0; x < base.width; ++x) {
                    const int ax = x * alphaMap->width / base.width;
                    const int ay = y * alphaMap->height / base.height;
                    const std::size_t source =
                        (std::size_t(ay) * std::size_t(alphaMap->width) + std::size_t(ax)) * 4;
                    base.rgba[(std::size_t(y) * std::size_t(base.width) + std::size_t(x)) * 4 + 3] =
                        alphaMap->rgba[source + (ownAlpha ? 3 : 0)];
                }
            }
            current->alphaMasked = true;
        }
        alphaMap.reset();
    };
    const std::filesystem::path folder = library.parent_path();
    while (std::getline(lines, line)) {
        ++number;
        const std::vector<std::string> words = splitWords(line.substr(0, line.find('#')));
        if (words.empty()) {
            continue;
        }
        const std::string where = library.string() + ":" + std::to_string(number) + ": ";
        const std::string& keyword = words[0];
        if (keyword == "newmtl") {
            finishMaterial();
            if (words.size() < 2) {
                return Error{where + "newmtl needs a name"};
            }
            byName[words[1]] = int(materials.size());
            materials.emplace_back();
            materials.back().name = words[1];
            current = &materials.back();
            continue;
        }
        if (current == nullptr) {
            continue;  // statements before the first newmtl have nothing to apply to
        }
        if (keyword == "Kd") {
            glm::vec3 colour;
            if (words.size() < 4 || !parseFloat(words[1], colour.r) ||
                !parseFloat(words[2], colour.g) || !parseFloat(words[3], colour.b)) {
                return Error{where + "Kd needs three numbers"};
            }
            current->baseColor = glm::vec4(colour, current->baseColor.a);
        } else if (keyword == "d" || keyword == "Tr") {
            float value;
            if (words.size() < 2 || !parseFloat(words.back(), value)) {
                return Error{where + keyword + " needs a number"};
            }
            current->baseColor.a = keyword == "d" ? value : 1.0f - value;
        } else if (keyword == "map_Kd" || keyword == "map_d") {
            const std::string name = mapFileName(words);
            if (name.empty()) {
                return Error{where + keyword + " needs a file name"};
            }
            Result<PlantTexture> texture = readTexture(library, number, folder / name);
            if (!texture) {
                return texture.error();
            }
            if (keyword == "map_Kd") {
                current->baseColorTexture = std::move(*texture);
            } else {
                alphaMap = std::move(*texture);
            }
        }
    }
    finishMaterial();
    return Status::success();
}

Result<PlantModel> importObj(const std::filesystem::path& path, const PlantImportOptions& options) {
    Result<std::string> text = readFile(path);
    if (!text) {
        return text.error();
    }
    std::vector<glm::vec3> positions;
    std::vector<glm::vec2> uvs;
    std::vector<glm::vec3> normals;
    std::vector<PlantMaterial> materials;
    std::map<std::string, int> materialByName;
    std::vector<NamedMesh> named;
    std::map<std::pair<std::string, int>, std::size_t> meshByKey;
    std::vector<std::map<std::array<int, 3>, std::uint32_t>> corners;
    std::string group;
    int material = -1;

    std::istringstream lines(*text);
    std::string line;
    int number = 0;
    while (std::getline(lines, line)) {
        ++number;
        const std::vector<std::string> words = splitWords(line.substr(0, line.find('#')));
        if (words.empty()) {
            continue;
        }
        const std::string where = path.string() + ":" + std::to_string(number) + ": ";
        const std::string& keyword = words[0];
        if (keyword == "v" || keyword == "vn") {
            glm::vec3 v;
            if (words.size() < 4 || !parseFloat(words[1], v.x) || !parseFloat(words[2], v.y) ||
                !parseFloat(words[3], v.z)) {
                return Error{where + keyword + " needs three numbers"};
            }
            (keyword == "v" ? positions : normals).push_back(v);
        } else if (keyword == "vt") {
            glm::vec2 t;
            if (words.size() < 3 || !parseFloat(words[1], t.x) || !parseFloat(words[2], t.y)) {
                return Error{where + "vt needs two numbers"};
            }
            uvs.push_back(t);
        } else if (keyword == "o" || keyword == "g") {
            group = words.size() > 1 ? words[1] : "";
        } else if (keyword == "usemtl") {
            if (words.size() < 2 || materialByName.count(words[1]) == 0) {
                return Error{where + "unknown material '" + (words.size() > 1 ? words[1] : "") +
                             "'"};
            }
            material = materialByName[words[1]];
        } else if (keyword == "mtllib") {
            const std::string name = mapFileName(words);
            const std::filesystem::path library = path.parent_path() / name;
            std::error_code error;
            if (!std::filesystem::exists(library, error)) {
                return Error{where + "material library '" + name + "' not found"};
            }
            if (Status read = readMaterialLibrary(library, materials, materialByName); !read) {
                return read.error();
            }
        } else if (keyword == "l" || keyword == "p") {
            return Error{where + "unsupported element '" + keyword +
                         "' (only triangles and polygons)"};
        } else if (keyword == "f") {
            if (words.size() < 4) {
                return Error{where + "a face needs at least 3 vertices"};
            }
            const std::pair<std::string, int> key(group, material);
            auto [it, inserted] = meshByKey.emplace(key, named.size());
            if (inserted) {
                NamedMesh entry;
                entry.meshName = group;
                entry.nodeName = group;
                entry.mesh.name = group;
                entry.mesh.material = material;
                entry.materialName = material >= 0 ? materials[std::size_t(material)].name : "";
                named.push_back(std::move(entry));
                corners.emplace_back();
            }
            NamedMesh& entry = named[it->second];
            std::vector<std::uint32_t> face;
            for (std::size_t w = 1; w < words.size(); ++w) {
                std::array<int, 3> corner = {0, 0, 0};
                std::array<std::size_t, 3> sizes = {positions.size(), uvs.size(), normals.size()};
                static const std::array<const char*, 3> kinds = {"vertex", "texture coordinate",
                                                                 "normal"};
                std::size_t field = 0;
                std::size_t start = 0;
                const std::string& word = words[w];
                while (field < 3) {
                    const std::size_t slash = word.find('/', start);
                    const std::string part = word.substr(
                        start, slash == std::string::npos ? std::string::npos : slash - start);
                    if (!part.empty()) {
                        int value = 0;
                        auto [ptr, ec] =
                            std::from_chars(part.data(), part.data() + part.size(), value);
                        if (ec != std::errc() || ptr != part.data() + part.size() || value == 0) {
                            return Error{where + "bad face index '" + part + "'"};
                        }
                        const long long resolved =
                            value > 0 ? value : (long long)(sizes[field]) + value + 1;
                        if (resolved < 1 || resolved > (long long)(sizes[field])) {
                            return Error{where + "face " + kinds[field] + " index " +
                                         std::to_string(value) + " out of range (" +
                                         std::to_string(sizes[field]) + " defined)"};
                        }
                        corner[field] = int(resolved);
                    } else if (field == 0) {
                        return Error{where + "a face corner needs a vertex index"};
                    }
                    ++field;
                    if (slash == std::string::npos) {
                        break;
                    }
                    start = slash + 1;
                }
                auto [cornerIt, isNew] =
                    corners[it->second].emplace(corner, std::uint32_t(entry.mesh.positions.size()));
                if (isNew) {
                    entry.mesh.positions.push_back(toModel(positions[std::size_t(corner[0] - 1)]));
                    // OBJ texture rows start at the bottom; PlantTexture rows at the top.
                    const glm::vec2 uv =
                        corner[1] > 0 ? uvs[std::size_t(corner[1] - 1)] : glm::vec2(0.0f);
                    entry.mesh.uvs.emplace_back(uv.x, 1.0f - uv.y);
                    entry.mesh.normals.push_back(
                        corner[2] > 0 ? toModel(glm::normalize(normals[std::size_t(corner[2] - 1)]))
                                      : glm::vec3(0.0f));
                }
                face.push_back(cornerIt->second);
            }
            for (std::size_t k = 2; k < face.size(); ++k) {
                entry.mesh.indices.insert(entry.mesh.indices.end(),
                                          {face[0], face[k - 1], face[k]});
            }
        }
    }
    for (NamedMesh& entry : named) {
        // Corners without normals got zero vectors: recompute the whole mesh's then.
        const bool missing = std::any_of(entry.mesh.normals.begin(), entry.mesh.normals.end(),
                                         [](const glm::vec3& n) { return n == glm::vec3(0.0f); });
        if (missing) {
            entry.mesh.normals.clear();
        }
    }
    return finish(path, std::move(named), std::move(materials), {}, options);
}

}  // namespace

Result<PlantModel> PlantImporter::import(const std::filesystem::path& path,
                                         const PlantImportOptions& options) {
    std::error_code error;
    if (!std::filesystem::is_regular_file(path, error)) {
        return Error{path.string() + ": file not found"};
    }
    const std::string extension = lowercase(path.extension().string());
    // Library exceptions (allocation, nlohmann) stop here, as errors naming the file.
    try {
        if (extension == ".gltf" || extension == ".glb") {
            return importGltf(path, options);
        }
        if (extension == ".obj") {
            return importObj(path, options);
        }
    } catch (const std::exception& e) {
        return Error{path.string() + ": cannot import: " + e.what()};
    }
    return Error{path.string() + ": unsupported plant file type '" + extension +
                 "' (use .gltf, .glb or .obj)"};
}

}  // namespace sylva
