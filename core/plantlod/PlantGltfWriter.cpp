#include "sylva/core/plantlod/PlantGltfWriter.h"

#include "sylva/core/base/AtomicFile.h"

#include <stb_image_write.h>
#include <unistd.h>

#include <atomic>
#include <cstring>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>

namespace sylva {

namespace {

using Json = nlohmann::ordered_json;

constexpr int kFloat = 5126;
constexpr int kUnsignedInt = 5125;
constexpr int kArrayBuffer = 34962;
constexpr int kElementArrayBuffer = 34963;

// Model frame (+Z up) to glTF (+Y up): (x, y, z) → (x, z, −y).
glm::vec3 toGltf(const glm::vec3& v) {
    return {v.x, v.z, -v.y};
}

std::string base64(const std::string& bytes) {
    static const char* alphabet =
        "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    out.reserve((bytes.size() + 2) / 3 * 4);
    std::size_t i = 0;
    for (; i + 2 < bytes.size(); i += 3) {
        const std::uint32_t n = (std::uint32_t(std::uint8_t(bytes[i])) << 16) |
                                (std::uint32_t(std::uint8_t(bytes[i + 1])) << 8) |
                                std::uint8_t(bytes[i + 2]);
        out += alphabet[(n >> 18) & 63];
        out += alphabet[(n >> 12) & 63];
        out += alphabet[(n >> 6) & 63];
        out += alphabet[n & 63];
    }
    if (i < bytes.size()) {
        std::uint32_t n = std::uint32_t(std::uint8_t(bytes[i])) << 16;
        if (i + 1 < bytes.size()) {
            n |= std::uint32_t(std::uint8_t(bytes[i + 1])) << 8;
        }
        out += alphabet[(n >> 18) & 63];
        out += alphabet[(n >> 12) & 63];
        out += i + 1 < bytes.size() ? alphabet[(n >> 6) & 63] : '=';
        out += '=';
    }
    return out;
}

void appendPng(void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data), std::size_t(size));
}

std::string encodePng(const PlantTexture& texture) {
    std::string png;
    stbi_write_png_to_func(appendPng, &png, texture.width, texture.height, 4, texture.rgba.data(),
                           texture.width * 4);
    return png;
}

// Binary buffer under construction: views 4-byte aligned (glTF requires alignment to
// the component size).
struct BufferBuilder {
    std::string bytes;
    Json views = Json::array();

    int addView(const void* data, std::size_t size, int target) {
        while (bytes.size() % 4 != 0) {
            bytes.push_back('\0');
        }
        Json view = {{"buffer", 0}, {"byteOffset", bytes.size()}, {"byteLength", size}};
        if (target != 0) {
            view["target"] = target;
        }
        bytes.append(static_cast<const char*>(data), size);
        views.push_back(view);
        return int(views.size()) - 1;
    }
};

Json vectorJson(const glm::vec3& v) {
    return Json::array({v.x, v.y, v.z});
}

}  // namespace

Result<std::string> PlantGltfWriter::encode(const PlantModel& model, bool binary) {
    for (const PlantMesh& mesh : model.meshes) {
        const bool consistent = mesh.normals.size() == mesh.positions.size() &&
                                (mesh.uvs.empty() || mesh.uvs.size() == mesh.positions.size()) &&
                                mesh.indices.size() % 3 == 0 && !mesh.positions.empty() &&
                                mesh.material < int(model.materials.size());
        if (!consistent) {
            return Error{"plant '" + model.name + "' mesh '" + mesh.name +
                         "': inconsistent vertex arrays, indices or material"};
        }
        for (std::uint32_t index : mesh.indices) {
            if (index >= mesh.positions.size()) {
                return Error{"plant '" + model.name + "' mesh '" + mesh.name +
                             "': index out of range"};
            }
        }
    }
    BufferBuilder buffer;
    Json gltf;
    gltf["asset"] = {{"version", "2.0"}, {"generator", "Sylva"}};
    Json skeleton = Json::array();
    for (const SkeletonSegment& segment : model.skeleton) {
        skeleton.push_back({{"start", vectorJson(toGltf(segment.start))},
                            {"end", vectorJson(toGltf(segment.end))},
                            {"startRadius", segment.startRadius},
                            {"endRadius", segment.endRadius},
                            {"parent", segment.parent}});
    }
    gltf["asset"]["extras"] = {{"sylva_skeleton", skeleton}};
    gltf["scene"] = 0;

    Json images = Json::array();
    Json textures = Json::array();
    Json materials = Json::array();
    for (const PlantMaterial& material : model.materials) {
        Json pbr = {{"baseColorFactor", Json::array({material.baseColor.r, material.baseColor.g,
                                                     material.baseColor.b, material.baseColor.a})},
                    {"metallicFactor", 0.0},
                    {"roughnessFactor", 1.0}};
        if (material.baseColorTexture.width > 0) {
            const std::string png = encodePng(material.baseColorTexture);
            Json image = {{"name", material.name}};
            if (binary) {
                image["bufferView"] = buffer.addView(png.data(), png.size(), 0);
                image["mimeType"] = "image/png";
            } else {
                image["uri"] = "data:image/png;base64," + base64(png);
            }
            images.push_back(image);
            textures.push_back({{"source", int(images.size()) - 1}});
            pbr["baseColorTexture"] = {{"index", int(textures.size()) - 1}};
        }
        Json entry = {
            {"name", material.name}, {"pbrMetallicRoughness", pbr}, {"doubleSided", true}};
        if (material.alphaMasked) {
            entry["alphaMode"] = "MASK";
            entry["alphaCutoff"] = material.alphaCutoff;
        }
        materials.push_back(entry);
    }

    Json accessors = Json::array();
    Json meshes = Json::array();
    Json nodes = Json::array();
    Json sceneNodes = Json::array();
    auto addAccessor = [&](int view, std::size_t count, int componentType, const char* type) {
        accessors.push_back({{"bufferView", view},
                             {"componentType", componentType},
                             {"count", count},
                             {"type", type}});
        return int(accessors.size()) - 1;
    };
    for (const PlantMesh& mesh : model.meshes) {
        std::vector<glm::vec3> positions(mesh.positions.size());
        std::vector<glm::vec3> normals(mesh.normals.size());
        glm::vec3 minimum(std::numeric_limits<float>::max());
        glm::vec3 maximum(std::numeric_limits<float>::lowest());
        for (std::size_t i = 0; i < positions.size(); ++i) {
            positions[i] = toGltf(mesh.positions[i]);
            minimum = glm::min(minimum, positions[i]);
            maximum = glm::max(maximum, positions[i]);
            normals[i] = toGltf(mesh.normals[i]);
        }
        Json attributes;
        const int position = addAccessor(
            buffer.addView(positions.data(), positions.size() * sizeof(glm::vec3), kArrayBuffer),
            positions.size(), kFloat, "VEC3");
        accessors[std::size_t(position)]["min"] = vectorJson(minimum);
        accessors[std::size_t(position)]["max"] = vectorJson(maximum);
        attributes["POSITION"] = position;
        attributes["NORMAL"] = addAccessor(
            buffer.addView(normals.data(), normals.size() * sizeof(glm::vec3), kArrayBuffer),
            normals.size(), kFloat, "VEC3");
        if (!mesh.uvs.empty()) {
            attributes["TEXCOORD_0"] = addAccessor(
                buffer.addView(mesh.uvs.data(), mesh.uvs.size() * sizeof(glm::vec2), kArrayBuffer),
                mesh.uvs.size(), kFloat, "VEC2");
        }
        const int indices = addAccessor(
            buffer.addView(mesh.indices.data(), mesh.indices.size() * sizeof(std::uint32_t),
                           kElementArrayBuffer),
            mesh.indices.size(), kUnsignedInt, "SCALAR");
        Json primitive = {{"attributes", attributes}, {"indices", indices}, {"mode", 4}};
        if (mesh.material >= 0) {
            primitive["material"] = mesh.material;
        }
        meshes.push_back({{"name", mesh.name}, {"primitives", Json::array({primitive})}});
        nodes.push_back({{"name", mesh.name}, {"mesh", int(meshes.size()) - 1}});
        sceneNodes.push_back(int(nodes.size()) - 1);
    }
    gltf["scenes"] = Json::array({{{"name", model.name}, {"nodes", sceneNodes}}});
    gltf["nodes"] = nodes;
    gltf["meshes"] = meshes;
    gltf["materials"] = materials;
    if (!textures.empty()) {
        gltf["textures"] = textures;
        gltf["images"] = images;
    }
    gltf["accessors"] = accessors;
    gltf["bufferViews"] = buffer.views;
    while (buffer.bytes.size() % 4 != 0) {
        buffer.bytes.push_back('\0');
    }
    Json bufferEntry = {{"byteLength", buffer.bytes.size()}};
    if (!binary) {
        bufferEntry["uri"] = "data:application/octet-stream;base64," + base64(buffer.bytes);
    }
    gltf["buffers"] = Json::array({bufferEntry});

    std::string json = gltf.dump(binary ? -1 : 1);
    if (!binary) {
        return json + "\n";
    }
    // GLB: 12-byte header, JSON chunk padded with spaces, BIN chunk padded with zeros.
    while (json.size() % 4 != 0) {
        json.push_back(' ');
    }
    auto put32 = [](std::string& out, std::uint32_t value) {
        for (int i = 0; i < 4; ++i) {
            out.push_back(char((value >> (8 * i)) & 0xFF));
        }
    };
    std::string glb;
    const std::uint32_t total = std::uint32_t(12 + 8 + json.size() + 8 + buffer.bytes.size());
    put32(glb, 0x46546C67u);  // "glTF"
    put32(glb, 2);
    put32(glb, total);
    put32(glb, std::uint32_t(json.size()));
    put32(glb, 0x4E4F534Au);  // "JSON"
    glb += json;
    put32(glb, std::uint32_t(buffer.bytes.size()));
    put32(glb, 0x004E4942u);  // "BIN\0"
    glb += buffer.bytes;
    return glb;
}

Status PlantGltfWriter::write(const PlantModel& model, const std::filesystem::path& path) {
    const std::string extension = path.extension().string();
    if (extension != ".gltf" && extension != ".glb") {
        return Error{path.string() + ": unknown plant file type (use .gltf or .glb)"};
    }
    Result<std::string> bytes = encode(model, extension == ".glb");
    if (!bytes) {
        return Error{path.string() + ": " + bytes.error().message};
    }
    std::error_code error;
    const std::filesystem::path folder = path.has_parent_path() ? path.parent_path() : ".";
    std::filesystem::create_directories(folder, error);
    if (error) {
        return Error{path.string() + ": cannot create folder '" + folder.string() +
                     "': " + error.message()};
    }
    const Status written = writeFileAtomically(path, *bytes);
    if (!written) {
        return Error{path.string() + ": " + written.error().message};
    }
    return Status::success();
}

}  // namespace sylva
