#include "GltfPlantReader.h"

#include <array>
#include <cstring>
#include <numeric>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <nlohmann/json.hpp>

#include "GltfAccessors.h"
#include "GltfSkeleton.h"
#include "ImportedPlant.h"
#include "sylva/core/image/GltfImageDecoder.h"

namespace sylva::plantimport {

namespace {

using Json = nlohmann::json;

// ---------------------------------------------------------------------------- the file

// The file's bytes and its JSON (the first chunk of a GLB).
struct GltfFile {
    std::string bytes;
    bool binary = false;
    Json json;
};

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

// Reads the file and parses its JSON: a glTF 2.x asset.
Result<GltfFile> readGltfFile(const std::filesystem::path& path) {
    Result<std::string> bytes = readWholeFile(path);
    if (!bytes) {
        return bytes.error();
    }
    GltfFile file;
    file.bytes = std::move(*bytes);
    file.binary = file.bytes.size() >= 4 && file.bytes.compare(0, 4, "glTF") == 0;
    if (path.extension() == ".glb" && !file.binary) {
        if (file.bytes.size() < 4) {
            return Error{path.string() + ": truncated GLB: " + std::to_string(file.bytes.size()) +
                         " bytes, less than the 20-byte header"};
        }
        return Error{path.string() + ": not a GLB file (bad magic)"};
    }
    std::string jsonText = file.bytes;
    if (file.binary) {
        Result<std::string> chunk = glbJson(path, file.bytes);
        if (!chunk) {
            return chunk.error();
        }
        jsonText = *chunk;
    }
    try {
        file.json = Json::parse(jsonText);
    } catch (const Json::parse_error& e) {
        return Error{path.string() + ": corrupt glTF: invalid JSON at byte " +
                     std::to_string(e.byte)};
    }
    if (!file.json.is_object() || !file.json.contains("asset") || !file.json["asset"].is_object()) {
        return Error{path.string() + ": corrupt glTF: no \"asset\" object"};
    }
    const std::string version = file.json["asset"].value("version", "");
    if (version.rfind("2.", 0) != 0) {
        return Error{path.string() + ": unsupported glTF version '" + version + "' (only 2.x)"};
    }
    return file;
}

// Required extensions we cannot honour, and buffers or images whose files are missing.
Status checkSupported(const std::filesystem::path& path, const Json& json) {
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
    return Status::success();
}

Result<tinygltf::Model> loadModel(const std::filesystem::path& path, const GltfFile& file) {
    tinygltf::Model gltf;
    tinygltf::TinyGLTF loader;
    std::string error;
    std::string warning;
    const std::string folder = path.parent_path().string();
    bool loaded;
    if (file.binary) {
        loaded = loader.LoadBinaryFromMemory(
            &gltf, &error, &warning, reinterpret_cast<const unsigned char*>(file.bytes.data()),
            unsigned(file.bytes.size()), folder);
    } else {
        loaded = loader.LoadASCIIFromString(&gltf, &error, &warning, file.bytes.data(),
                                            unsigned(file.bytes.size()), folder);
    }
    if (!loaded) {
        const std::string firstLine = error.substr(0, error.find('\n'));
        return Error{path.string() + ": corrupt glTF: " +
                     (firstLine.empty() ? "tinygltf could not load it" : firstLine)};
    }
    return gltf;
}

// ---------------------------------------------------------------------------- materials

// The image through the shared glTF image decoder (core/image/GltfImageDecoder).
Result<PlantTexture> decodeImage(const std::filesystem::path& path, const tinygltf::Image& image,
                                 int index) {
    Result<RgbaImage> decoded = decodeGltfImage(path, image, index);
    if (!decoded) {
        return decoded.error();
    }
    PlantTexture texture;
    texture.width = decoded.value().width;
    texture.height = decoded.value().height;
    texture.rgba = std::move(decoded.value().pixels);
    return texture;
}

Result<PlantMaterial> readMaterial(const std::filesystem::path& path, const tinygltf::Model& gltf,
                                   std::size_t index) {
    const tinygltf::Material& source = gltf.materials[index];
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
    if (textureIndex < 0) {
        return material;
    }
    if (std::size_t(textureIndex) >= gltf.textures.size() ||
        gltf.textures[std::size_t(textureIndex)].source < 0 ||
        std::size_t(gltf.textures[std::size_t(textureIndex)].source) >= gltf.images.size()) {
        return Error{path.string() + ": material " + std::to_string(index) +
                     " refers to a missing texture"};
    }
    const int imageIndex = gltf.textures[std::size_t(textureIndex)].source;
    Result<PlantTexture> texture =
        decodeImage(path, gltf.images[std::size_t(imageIndex)], imageIndex);
    if (!texture) {
        return texture.error();
    }
    material.baseColorTexture = std::move(*texture);
    return material;
}

// ---------------------------------------------------------------------------- meshes

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

// The default scene's root nodes; without scenes, every node that is nobody's child.
std::vector<int> sceneRoots(const tinygltf::Model& gltf) {
    const int sceneIndex = gltf.defaultScene >= 0 ? gltf.defaultScene : 0;
    if (std::size_t(sceneIndex) < gltf.scenes.size()) {
        return gltf.scenes[std::size_t(sceneIndex)].nodes;
    }
    std::vector<bool> isChild(gltf.nodes.size(), false);
    for (const tinygltf::Node& node : gltf.nodes) {
        for (int child : node.children) {
            if (child >= 0 && std::size_t(child) < isChild.size()) {
                isChild[std::size_t(child)] = true;
            }
        }
    }
    std::vector<int> roots;
    for (std::size_t i = 0; i < gltf.nodes.size(); ++i) {
        if (!isChild[i]) {
            roots.push_back(int(i));
        }
    }
    return roots;
}

// One primitive's triangles as a list: strips and fans unrolled, lists checked.
Result<std::vector<std::uint32_t>> triangleList(int mode, std::vector<std::uint32_t> indices,
                                                const std::string& where) {
    std::vector<std::uint32_t> triangles;
    if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
        for (std::size_t i = 2; i < indices.size(); ++i) {
            if (i % 2 == 0) {
                triangles.insert(triangles.end(), {indices[i - 2], indices[i - 1], indices[i]});
            } else {
                triangles.insert(triangles.end(), {indices[i - 1], indices[i - 2], indices[i]});
            }
        }
    } else if (mode == TINYGLTF_MODE_TRIANGLE_FAN) {
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
    return triangles;
}

// A node's placement: positions by `matrix`, normals by its inverse transpose.
struct Placement {
    glm::dmat4 matrix;
    glm::dmat3 normalMatrix;
    bool mirrored;  // a negative determinant: triangles turn to keep their front
};

// Transformed normals and the uvs of a primitive with `count` vertices.
Status readNormalsAndUvs(const std::filesystem::path& path, const tinygltf::Model& gltf,
                         const tinygltf::Primitive& primitive, const Placement& placement,
                         std::size_t count, const std::string& where, PlantMesh& mesh) {
    if (auto it = primitive.attributes.find("NORMAL"); it != primitive.attributes.end()) {
        Result<std::vector<float>> normals = readGltfFloats(path, gltf, it->second, 3);
        if (!normals) {
            return normals.error();
        }
        if (normals->size() != 3 * count) {
            return Error{where + ": NORMAL and POSITION counts differ"};
        }
        for (std::size_t i = 0; i < count; ++i) {
            glm::dvec3 n =
                placement.normalMatrix *
                glm::dvec3((*normals)[3 * i], (*normals)[3 * i + 1], (*normals)[3 * i + 2]);
            const double length = glm::length(n);
            mesh.normals.push_back(toModelFrame(glm::vec3(length > 0.0 ? n / length : n)));
        }
    }
    if (auto it = primitive.attributes.find("TEXCOORD_0"); it != primitive.attributes.end()) {
        Result<std::vector<float>> uvs = readGltfFloats(path, gltf, it->second, 2);
        if (!uvs) {
            return uvs.error();
        }
        if (uvs->size() / 2 != count) {
            return Error{where + ": TEXCOORD_0 and POSITION counts differ"};
        }
        for (std::size_t i = 0; i < count; ++i) {
            mesh.uvs.emplace_back((*uvs)[2 * i], (*uvs)[2 * i + 1]);
        }
    }
    return Status::success();
}

// The primitive's indices (0 … count − 1 without an index accessor), each checked.
Result<std::vector<std::uint32_t>> readPrimitiveIndices(const std::filesystem::path& path,
                                                        const tinygltf::Model& gltf,
                                                        const tinygltf::Primitive& primitive,
                                                        std::size_t count,
                                                        const std::string& where) {
    std::vector<std::uint32_t> indices;
    if (primitive.indices >= 0) {
        Result<std::vector<std::uint32_t>> read = readGltfIndices(path, gltf, primitive.indices);
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
    return indices;
}

// Primitive `p` of the mesh of `node`, placed in the model frame.
Result<ImportedMesh> readPrimitive(const std::filesystem::path& path, const tinygltf::Model& gltf,
                                   const tinygltf::Node& node, std::size_t p,
                                   const Placement& placement,
                                   const std::vector<PlantMaterial>& materials) {
    const tinygltf::Mesh& mesh = gltf.meshes[std::size_t(node.mesh)];
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
    Result<std::vector<float>> positions = readGltfFloats(path, gltf, positionIt->second, 3);
    if (!positions) {
        return positions.error();
    }
    const std::size_t count = positions->size() / 3;
    ImportedMesh entry;
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
            placement.matrix *
            glm::dvec4((*positions)[3 * i], (*positions)[3 * i + 1], (*positions)[3 * i + 2], 1.0);
        entry.mesh.positions.push_back(toModelFrame(glm::vec3(p4)));
    }
    if (Status read = readNormalsAndUvs(path, gltf, primitive, placement, count, where, entry.mesh);
        !read) {
        return read.error();
    }
    Result<std::vector<std::uint32_t>> indices =
        readPrimitiveIndices(path, gltf, primitive, count, where);
    if (!indices) {
        return indices.error();
    }
    Result<std::vector<std::uint32_t>> triangles =
        triangleList(primitive.mode, std::move(*indices), where);
    if (!triangles) {
        return triangles.error();
    }
    if (placement.mirrored) {
        for (std::size_t i = 0; i + 2 < triangles->size(); i += 3) {
            std::swap((*triangles)[i + 1], (*triangles)[i + 2]);
        }
    }
    entry.mesh.indices = std::move(*triangles);
    return entry;
}

// Depth-first over the scene graph with accumulated transforms: every primitive.
Result<std::vector<ImportedMesh>> readScene(const std::filesystem::path& path,
                                            const tinygltf::Model& gltf,
                                            const std::vector<int>& roots,
                                            const std::vector<PlantMaterial>& materials) {
    std::vector<ImportedMesh> meshes;
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
        const Placement placement{matrix, glm::transpose(glm::inverse(glm::dmat3(matrix))),
                                  glm::determinant(glm::dmat3(matrix)) < 0.0};
        const std::size_t primitives = gltf.meshes[std::size_t(node.mesh)].primitives.size();
        for (std::size_t p = 0; p < primitives; ++p) {
            Result<ImportedMesh> entry = readPrimitive(path, gltf, node, p, placement, materials);
            if (!entry) {
                return entry.error();
            }
            meshes.push_back(std::move(*entry));
        }
    }
    return meshes;
}

}  // namespace

Result<PlantModel> readGltfPlant(const std::filesystem::path& path,
                                 const PlantImportOptions& options) {
    Result<GltfFile> file = readGltfFile(path);
    if (!file) {
        return file.error();
    }
    if (Status supported = checkSupported(path, file->json); !supported) {
        return supported.error();
    }
    Result<tinygltf::Model> gltf = loadModel(path, *file);
    if (!gltf) {
        return gltf.error();
    }
    std::vector<PlantMaterial> materials;
    for (std::size_t i = 0; i < gltf->materials.size(); ++i) {
        Result<PlantMaterial> material = readMaterial(path, *gltf, i);
        if (!material) {
            return material.error();
        }
        materials.push_back(std::move(*material));
    }
    const std::vector<int> roots = sceneRoots(*gltf);
    Result<std::vector<ImportedMesh>> meshes = readScene(path, *gltf, roots, materials);
    if (!meshes) {
        return meshes.error();
    }
    std::vector<SkeletonSegment> skeleton;
    if (options.useFileSkeleton) {
        Result<std::vector<SkeletonSegment>> read = readGltfSkeleton(path, file->json, roots);
        if (!read) {
            return read.error();
        }
        skeleton = std::move(*read);
    }
    return assemblePlantModel(path, std::move(*meshes), std::move(materials), std::move(skeleton),
                              options);
}

}  // namespace sylva::plantimport
