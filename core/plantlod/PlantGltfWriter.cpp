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

Status checkMeshes(const PlantModel& model) {
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
    return Status::success();
}

// asset.extras.sylva_skeleton (read back by the importer's GltfSkeleton).
Json skeletonJson(const std::vector<SkeletonSegment>& segments) {
    Json skeleton = Json::array();
    for (const SkeletonSegment& segment : segments) {
        skeleton.push_back({{"start", vectorJson(toGltf(segment.start))},
                            {"end", vectorJson(toGltf(segment.end))},
                            {"startRadius", segment.startRadius},
                            {"endRadius", segment.endRadius},
                            {"parent", segment.parent}});
    }
    return skeleton;
}

// The glTF arrays under construction; materials first (their PNGs come first in the
// binary buffer), then one node with one primitive per mesh.
class GltfDocument {
public:
    explicit GltfDocument(bool binary) : binary_(binary) {}

    void addMaterial(const PlantMaterial& material) {
        Json pbr = {{"baseColorFactor", Json::array({material.baseColor.r, material.baseColor.g,
                                                     material.baseColor.b, material.baseColor.a})},
                    {"metallicFactor", 0.0},
                    {"roughnessFactor", 1.0}};
        if (material.baseColorTexture.width > 0) {
            const std::string png = encodePng(material.baseColorTexture);
            Json image = {{"name", material.name}};
            if (binary_) {
                image["bufferView"] = buffer_.addView(png.data(), png.size(), 0);
                image["mimeType"] = "image/png";
            } else {
                image["uri"] = "data:image/png;base64," + base64(png);
            }
            images_.push_back(image);
            textures_.push_back({{"source", int(images_.size()) - 1}});
            pbr["baseColorTexture"] = {{"index", int(textures_.size()) - 1}};
        }
        Json entry = {
            {"name", material.name}, {"pbrMetallicRoughness", pbr}, {"doubleSided", true}};
        if (material.alphaMasked) {
            entry["alphaMode"] = "MASK";
            entry["alphaCutoff"] = material.alphaCutoff;
        }
        materials_.push_back(entry);
    }

    void addMesh(const PlantMesh& mesh) {
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
        const int position = addAccessor(positions.data(), positions.size(), sizeof(glm::vec3),
                                         kArrayBuffer, kFloat, "VEC3");
        accessors_[std::size_t(position)]["min"] = vectorJson(minimum);
        accessors_[std::size_t(position)]["max"] = vectorJson(maximum);
        attributes["POSITION"] = position;
        attributes["NORMAL"] = addAccessor(normals.data(), normals.size(), sizeof(glm::vec3),
                                           kArrayBuffer, kFloat, "VEC3");
        if (!mesh.uvs.empty()) {
            attributes["TEXCOORD_0"] = addAccessor(mesh.uvs.data(), mesh.uvs.size(),
                                                   sizeof(glm::vec2), kArrayBuffer, kFloat, "VEC2");
        }
        const int indices =
            addAccessor(mesh.indices.data(), mesh.indices.size(), sizeof(std::uint32_t),
                        kElementArrayBuffer, kUnsignedInt, "SCALAR");
        Json primitive = {{"attributes", attributes}, {"indices", indices}, {"mode", 4}};
        if (mesh.material >= 0) {
            primitive["material"] = mesh.material;
        }
        meshes_.push_back({{"name", mesh.name}, {"primitives", Json::array({primitive})}});
        nodes_.push_back({{"name", mesh.name}, {"mesh", int(meshes_.size()) - 1}});
        sceneNodes_.push_back(int(nodes_.size()) - 1);
    }

    // Stores the arrays into `gltf` in the order of the format's examples; the buffer
    // is embedded as base64 unless binary (then it is the GLB's BIN chunk).
    void finish(const std::string& sceneName, Json& gltf) {
        gltf["scenes"] = Json::array({{{"name", sceneName}, {"nodes", sceneNodes_}}});
        gltf["nodes"] = nodes_;
        gltf["meshes"] = meshes_;
        gltf["materials"] = materials_;
        if (!textures_.empty()) {
            gltf["textures"] = textures_;
            gltf["images"] = images_;
        }
        gltf["accessors"] = accessors_;
        gltf["bufferViews"] = buffer_.views;
        while (buffer_.bytes.size() % 4 != 0) {
            buffer_.bytes.push_back('\0');
        }
        Json bufferEntry = {{"byteLength", buffer_.bytes.size()}};
        if (!binary_) {
            bufferEntry["uri"] = "data:application/octet-stream;base64," + base64(buffer_.bytes);
        }
        gltf["buffers"] = Json::array({bufferEntry});
    }

    const std::string& bufferBytes() const { return buffer_.bytes; }

private:
    int addAccessor(const void* data, std::size_t count, std::size_t elementSize, int target,
                    int componentType, const char* type) {
        const int view = buffer_.addView(data, count * elementSize, target);
        accessors_.push_back({{"bufferView", view},
                              {"componentType", componentType},
                              {"count", count},
                              {"type", type}});
        return int(accessors_.size()) - 1;
    }

    bool binary_;
    BufferBuilder buffer_;
    Json images_ = Json::array();
    Json textures_ = Json::array();
    Json materials_ = Json::array();
    Json accessors_ = Json::array();
    Json meshes_ = Json::array();
    Json nodes_ = Json::array();
    Json sceneNodes_ = Json::array();
};

// GLB: 12-byte header, JSON chunk padded with spaces, BIN chunk padded with zeros.
std::string glbContainer(std::string json, const std::string& binary) {
    while (json.size() % 4 != 0) {
        json.push_back(' ');
    }
    auto put32 = [](std::string& out, std::uint32_t value) {
        for (int i = 0; i < 4; ++i) {
            out.push_back(char((value >> (8 * i)) & 0xFF));
        }
    };
    std::string glb;
    const std::uint32_t total = std::uint32_t(12 + 8 + json.size() + 8 + binary.size());
    put32(glb, 0x46546C67u);  // "glTF"
    put32(glb, 2);
    put32(glb, total);
    put32(glb, std::uint32_t(json.size()));
    put32(glb, 0x4E4F534Au);  // "JSON"
    glb += json;
    put32(glb, std::uint32_t(binary.size()));
    put32(glb, 0x004E4942u);  // "BIN\0"
    glb += binary;
    return glb;
}

}  // namespace

Result<std::string> PlantGltfWriter::encode(const PlantModel& model, bool binary) {
    if (Status valid = checkMeshes(model); !valid) {
        return valid.error();
    }
    Json gltf;
    gltf["asset"] = {{"version", "2.0"}, {"generator", "Sylva"}};
    gltf["asset"]["extras"] = {{"sylva_skeleton", skeletonJson(model.skeleton)}};
    gltf["scene"] = 0;
    GltfDocument document(binary);
    for (const PlantMaterial& material : model.materials) {
        document.addMaterial(material);
    }
    for (const PlantMesh& mesh : model.meshes) {
        document.addMesh(mesh);
    }
    document.finish(model.name, gltf);
    std::string json = gltf.dump(binary ? -1 : 1);
    if (!binary) {
        return json + "\n";
    }
    return glbContainer(std::move(json), document.bufferBytes());
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
