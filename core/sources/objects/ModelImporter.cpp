#include "sylva/core/sources/objects/ModelImporter.h"

#include "sylva/core/image/GltfImageDecoder.h"
#include "sylva/core/image/ImageWriter.h"
#include "sylva/core/sources/objects/MeshSimplifier.h"

// Accessors are read by the plant importer's checked readers (indices, strides, offsets
// and buffer bounds; normalized integer attributes allowed).
#include "../../plantlod/GltfAccessors.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#include <tiny_gltf.h>
#pragma GCC diagnostic pop

#include <glm/gtc/quaternion.hpp>

namespace sylva {

namespace {

// What the readers collect besides the model: the texture of every triangle of every part
// (-1: none), so splitByTexture can give each part one texture; the model textures by the
// file's image index (glTF) or image path (OBJ), each decoded once.
struct ImportState {
    std::vector<std::vector<int>> triangleTextures;  // per part, per triangle
    std::map<std::string, int> textureByKey;
};

std::uint32_t packLinear(const std::vector<double>& factor) {
    const auto encode = [](double linear) {
        linear = std::clamp(linear, 0.0, 1.0);
        const double s =
            linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
        return static_cast<std::uint32_t>(std::lround(s * 255.0));
    };
    if (factor.size() < 3) {
        return 0xffffffffu;
    }
    return encode(factor[0]) | (encode(factor[1]) << 8) | (encode(factor[2]) << 16) | (255u << 24);
}

// Flat normals for triangles whose vertices have none (normal left at zero).
void fillMissingNormals(MeshGeometry& geometry, std::size_t firstVertex, std::size_t firstIndex) {
    std::vector<glm::vec3> sums(geometry.vertices.size() - firstVertex, glm::vec3(0.0f));
    for (std::size_t i = firstIndex; i + 2 < geometry.indices.size(); i += 3) {
        const glm::vec3 a = geometry.vertices[geometry.indices[i]].position;
        const glm::vec3 b = geometry.vertices[geometry.indices[i + 1]].position;
        const glm::vec3 c = geometry.vertices[geometry.indices[i + 2]].position;
        const glm::vec3 n = glm::cross(b - a, c - a);
        for (int k = 0; k < 3; ++k) {
            sums[geometry.indices[i + std::size_t(k)] - firstVertex] += n;
        }
    }
    for (std::size_t v = firstVertex; v < geometry.vertices.size(); ++v) {
        MeshVertex& vertex = geometry.vertices[v];
        if (glm::length(vertex.normal) < 1e-6f) {
            const glm::vec3 n = sums[v - firstVertex];
            vertex.normal = glm::length(n) > 0 ? glm::normalize(n) : glm::vec3(0, 0, 1);
        }
    }
}

// ------------------------------------------------------------------------------ glTF

glm::dmat4 nodeTransform(const tinygltf::Node& node) {
    if (node.matrix.size() == 16) {
        glm::dmat4 m;
        for (int i = 0; i < 16; ++i) {
            m[i / 4][i % 4] = node.matrix[std::size_t(i)];
        }
        return m;
    }
    glm::dmat4 t(1.0), r(1.0), s(1.0);
    if (node.translation.size() == 3) {
        t[3] = glm::dvec4(node.translation[0], node.translation[1], node.translation[2], 1.0);
    }
    if (node.rotation.size() == 4) {
        r = glm::mat4_cast(
            glm::dquat(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]));
    }
    if (node.scale.size() == 3) {
        s[0][0] = node.scale[0];
        s[1][1] = node.scale[1];
        s[2][2] = node.scale[2];
    }
    return t * r * s;
}

// The model texture of material `materialIndex`'s base colour texture (decoded once per
// image), or -1 without one; `texCoord` gets the TEXCOORD set it reads.
Result<int> materialTexture(const std::string& file, const tinygltf::Model& gltf, int materialIndex,
                            MeshModel& model, ImportState& state, int& texCoord) {
    if (materialIndex < 0 || std::size_t(materialIndex) >= gltf.materials.size()) {
        return -1;
    }
    const tinygltf::TextureInfo& info =
        gltf.materials[std::size_t(materialIndex)].pbrMetallicRoughness.baseColorTexture;
    if (info.index < 0) {
        return -1;
    }
    if (std::size_t(info.index) >= gltf.textures.size() ||
        gltf.textures[std::size_t(info.index)].source < 0 ||
        std::size_t(gltf.textures[std::size_t(info.index)].source) >= gltf.images.size()) {
        return Error{file + ": material " + std::to_string(materialIndex) +
                     " refers to a missing texture"};
    }
    texCoord = info.texCoord;
    const int image = gltf.textures[std::size_t(info.index)].source;
    const std::string key = "image " + std::to_string(image);
    if (const auto found = state.textureByKey.find(key); found != state.textureByKey.end()) {
        return found->second;
    }
    Result<RgbaImage> decoded = decodeGltfImage(file, gltf.images[std::size_t(image)], image);
    if (!decoded) {
        return decoded.error();
    }
    model.textures.push_back(MeshTexture{decoded.value().width, decoded.value().height,
                                         std::move(decoded.value().pixels)});
    state.textureByKey[key] = int(model.textures.size()) - 1;
    return int(model.textures.size()) - 1;
}

Status appendPrimitive(const std::string& file, const tinygltf::Model& gltf,
                       const tinygltf::Primitive& primitive, MeshModel& model, ImportState& state,
                       MeshGeometry& geometry, std::vector<int>& triangleTextures) {
    if (primitive.mode != -1 && primitive.mode != TINYGLTF_MODE_TRIANGLES) {
        return Status::success();  // points and lines are not drawn
    }
    const auto position = primitive.attributes.find("POSITION");
    if (position == primitive.attributes.end()) {
        return Error{file + ": a mesh primitive has no POSITION"};
    }
    Result<std::vector<float>> positions =
        plantimport::readGltfFloats(file, gltf, position->second, 3);
    if (!positions) {
        return positions.error();
    }
    std::vector<float> normals, uvs;
    if (const auto normal = primitive.attributes.find("NORMAL");
        normal != primitive.attributes.end()) {
        Result<std::vector<float>> read =
            plantimport::readGltfFloats(file, gltf, normal->second, 3);
        if (!read) {
            return read.error();
        }
        normals = std::move(read.value());
    }
    int texCoord = 0;
    Result<int> texture = materialTexture(file, gltf, primitive.material, model, state, texCoord);
    if (!texture) {
        return texture.error();
    }
    if (texture.value() >= 0) {
        const auto found = primitive.attributes.find("TEXCOORD_" + std::to_string(texCoord));
        if (found == primitive.attributes.end()) {
            return Error{file + ": a textured mesh primitive has no TEXCOORD_" +
                         std::to_string(texCoord)};
        }
        Result<std::vector<float>> read = plantimport::readGltfFloats(file, gltf, found->second, 2);
        if (!read) {
            return read.error();
        }
        uvs = std::move(read.value());
    }
    const std::size_t count = positions.value().size() / 3;
    if (!uvs.empty() && uvs.size() != 2 * count) {
        return Error{file + ": a mesh primitive has " + std::to_string(uvs.size() / 2) +
                     " texture coordinates for " + std::to_string(count) + " positions"};
    }
    std::vector<std::uint32_t> indices;
    if (primitive.indices >= 0) {
        Result<std::vector<std::uint32_t>> read =
            plantimport::readGltfIndices(file, gltf, primitive.indices);
        if (!read) {
            return read.error();
        }
        indices = std::move(read.value());
    } else {
        for (std::uint32_t i = 0; i < count; ++i) {
            indices.push_back(i);
        }
    }
    std::uint32_t color = 0xffffffffu;
    if (primitive.material >= 0 && std::size_t(primitive.material) < gltf.materials.size()) {
        color = packLinear(
            gltf.materials[std::size_t(primitive.material)].pbrMetallicRoughness.baseColorFactor);
    }
    const std::size_t firstVertex = geometry.vertices.size(), firstIndex = geometry.indices.size();
    for (std::size_t i = 0; i < count; ++i) {
        MeshVertex vertex;
        vertex.position = glm::vec3(positions.value()[3 * i], positions.value()[3 * i + 1],
                                    positions.value()[3 * i + 2]);
        vertex.normal = normals.size() == 3 * count
                            ? glm::vec3(normals[3 * i], normals[3 * i + 1], normals[3 * i + 2])
                            : glm::vec3(0.0f);
        vertex.color = color;
        vertex.uv = uvs.empty() ? glm::vec2(0.0f) : glm::vec2(uvs[2 * i], uvs[2 * i + 1]);
        geometry.vertices.push_back(vertex);
    }
    for (std::size_t i = 0; i + 2 < indices.size(); i += 3) {
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t index = indices[i + std::size_t(k)];
            if (index >= count) {
                return Error{file + ": a triangle index (" + std::to_string(index) +
                             ") is beyond the " + std::to_string(count) + " vertices"};
            }
            geometry.indices.push_back(std::uint32_t(firstVertex) + index);
        }
        triangleTextures.push_back(texture.value());
    }
    fillMissingNormals(geometry, firstVertex, firstIndex);
    return Status::success();
}

Status addNode(const std::string& file, const tinygltf::Model& gltf, int index, int parent,
               MeshModel& model, ImportState& state, int depth) {
    if (index < 0 || std::size_t(index) >= gltf.nodes.size() || depth > 64) {
        return Error{file + ": node " + std::to_string(index) +
                     " does not exist or nests too deep"};
    }
    const tinygltf::Node& node = gltf.nodes[std::size_t(index)];
    ModelPart part;
    part.name = node.name.empty() ? "node" + std::to_string(index) : node.name;
    part.parent = parent;
    part.local = nodeTransform(node);
    part.axis = glm::dvec3(0.0, 1.0, 0.0);  // the node's up
    if (parent < 0) {
        // glTF +Y up, +Z forward → model +Z up, +Y forward: (x, y, z) ↦ (−x, z, y).
        glm::dmat4 axes(0.0);
        axes[0][0] = -1.0;
        axes[1][2] = 1.0;
        axes[2][1] = 1.0;
        axes[3][3] = 1.0;
        part.local = axes * part.local;
    }
    std::vector<int> triangleTextures;
    if (node.mesh >= 0 && std::size_t(node.mesh) < gltf.meshes.size()) {
        for (const tinygltf::Primitive& primitive :
             gltf.meshes[std::size_t(node.mesh)].primitives) {
            if (Status status = appendPrimitive(file, gltf, primitive, model, state, part.geometry,
                                                triangleTextures);
                !status) {
                return status;
            }
        }
    }
    model.parts.push_back(std::move(part));
    state.triangleTextures.push_back(std::move(triangleTextures));
    const int self = int(model.parts.size()) - 1;
    for (int child : node.children) {
        if (Status status = addNode(file, gltf, child, self, model, state, depth + 1); !status) {
            return status;
        }
    }
    return Status::success();
}

Status readGltf(const std::filesystem::path& path, bool binary, MeshModel& model,
                ImportState& state) {
    tinygltf::TinyGLTF loader;
    tinygltf::Model gltf;
    std::string error, warning;
    const bool ok = binary ? loader.LoadBinaryFromFile(&gltf, &error, &warning, path.string())
                           : loader.LoadASCIIFromFile(&gltf, &error, &warning, path.string());
    if (!ok) {
        while (!error.empty() && (error.back() == '\n' || error.back() == ' ')) {
            error.pop_back();
        }
        return Error{path.string() + ": not a readable glTF file: " +
                     (error.empty() ? std::string("unknown error") : error)};
    }
    std::vector<int> roots;
    if (gltf.defaultScene >= 0 && std::size_t(gltf.defaultScene) < gltf.scenes.size()) {
        roots = gltf.scenes[std::size_t(gltf.defaultScene)].nodes;
    } else if (!gltf.scenes.empty()) {
        roots = gltf.scenes.front().nodes;
    }
    for (int root : roots) {
        if (Status status = addNode(path.string(), gltf, root, -1, model, state, 0); !status) {
            return status;
        }
    }
    return Status::success();
}

// ------------------------------------------------------------------------------- OBJ

struct ObjMaterial {
    std::uint32_t color = 0xffffffffu;
    int texture = -1;  // index into MeshModel::textures
};

// The image file of a `map_Kd` line as a model texture (read once per path), or an error
// naming the MTL line. Options before the file name (-s, -o, ...) are not supported: the
// last word is the file.
Result<int> objTexture(const std::filesystem::path& file, const std::string& where,
                       MeshModel& model, ImportState& state) {
    const std::string key = file.lexically_normal().string();
    if (const auto found = state.textureByKey.find(key); found != state.textureByKey.end()) {
        return found->second;
    }
    int width = 0, height = 0;
    Result<std::vector<std::uint8_t>> pixels = ImageWriter::readRgba8(file, width, height);
    if (!pixels) {
        return Error{where + "map_Kd: " + pixels.error().message};
    }
    model.textures.push_back(MeshTexture{width, height, std::move(pixels.value())});
    state.textureByKey[key] = int(model.textures.size()) - 1;
    return int(model.textures.size()) - 1;
}

// The materials of an MTL file: Kd colours and map_Kd textures. A missing MTL file leaves
// the faces white (as viewers do); a texture that cannot be read is an error.
Result<std::map<std::string, ObjMaterial>> readMtl(const std::filesystem::path& path,
                                                   MeshModel& model, ImportState& state) {
    std::map<std::string, ObjMaterial> materials;
    std::ifstream in(path);
    std::string line, current;
    for (int number = 1; std::getline(in, line); ++number) {
        std::istringstream words(line);
        std::string keyword;
        words >> keyword;
        if (keyword == "newmtl") {
            words >> current;
            materials[current] = ObjMaterial{};
        } else if (keyword == "Kd" && !current.empty()) {
            double r = 1, g = 1, b = 1;
            words >> r >> g >> b;
            materials[current].color = packLinear({r, g, b});
        } else if (keyword == "map_Kd" && !current.empty()) {
            std::string word, file;
            while (words >> word) {
                file = word;
            }
            Result<int> texture =
                objTexture(path.parent_path() / file,
                           path.string() + ":" + std::to_string(number) + ": ", model, state);
            if (!texture) {
                return texture.error();
            }
            materials[current].texture = texture.value();
        }
    }
    return materials;
}

// One corner `v`, `v/vt`, `v//vn` or `v/vt/vn` as 1-based (or negative, relative) indices;
// 0 where absent. False on a malformed number.
bool parseCorner(const std::string& corner, int& v, int& t, int& n) {
    const std::size_t first = corner.find('/');
    const std::size_t second =
        first == std::string::npos ? std::string::npos : corner.find('/', first + 1);
    try {
        v = std::stoi(corner.substr(0, first));
        t = n = 0;
        if (first != std::string::npos) {
            const std::string uv = corner.substr(
                first + 1, second == std::string::npos ? std::string::npos : second - first - 1);
            t = uv.empty() ? 0 : std::stoi(uv);
        }
        if (second != std::string::npos && second + 1 < corner.size()) {
            n = std::stoi(corner.substr(second + 1));
        }
    } catch (...) {
        return false;
    }
    return true;
}

struct ObjLists {
    std::vector<glm::vec3> positions, normals;
    std::vector<glm::vec2> uvs;  // v flipped to the glTF convention (v down)
};

// An `f` line's polygon appended to the current part as a fan.
Status readFace(std::istringstream& words, const std::string& where, const ObjLists& lists,
                const ObjMaterial& material, MeshGeometry& geometry,
                std::vector<int>& triangleTextures) {
    const std::size_t firstVertex = geometry.vertices.size();
    std::string corner;
    while (words >> corner) {
        int vi = 0, ti = 0, ni = 0;
        if (!parseCorner(corner, vi, ti, ni)) {
            return Error{where + "bad face corner '" + corner + "'"};
        }
        const auto resolve = [](int i, std::size_t size) { return i < 0 ? int(size) + i : i - 1; };
        const int v = resolve(vi, lists.positions.size());
        const int t = resolve(ti, lists.uvs.size());
        const int n = resolve(ni, lists.normals.size());
        if (v < 0 || std::size_t(v) >= lists.positions.size() ||
            (ti != 0 && (t < 0 || std::size_t(t) >= lists.uvs.size())) ||
            (ni != 0 && (n < 0 || std::size_t(n) >= lists.normals.size()))) {
            return Error{where + "face corner '" + corner + "' refers to a missing vertex"};
        }
        geometry.vertices.push_back(
            MeshVertex{lists.positions[std::size_t(v)],
                       ni != 0 ? lists.normals[std::size_t(n)] : glm::vec3(0.0f), material.color,
                       ti != 0 ? lists.uvs[std::size_t(t)] : glm::vec2(0.0f)});
    }
    const std::size_t corners = geometry.vertices.size() - firstVertex;
    if (corners < 3) {
        return Error{where + "a face needs at least three corners"};
    }
    const std::size_t firstIndex = geometry.indices.size();
    for (std::size_t i = 1; i + 1 < corners; ++i) {
        geometry.indices.insert(geometry.indices.end(),
                                {std::uint32_t(firstVertex), std::uint32_t(firstVertex + i),
                                 std::uint32_t(firstVertex + i + 1)});
        triangleTextures.push_back(material.texture);
    }
    fillMissingNormals(geometry, firstVertex, firstIndex);
    return Status::success();
}

ModelPart objPart(const std::string& name) {
    ModelPart part;
    part.name = name;
    part.axis = glm::dvec3(0.0, 0.0, 1.0);
    return part;
}

Status readObj(const std::filesystem::path& path, MeshModel& model, ImportState& state) {
    std::ifstream in(path);
    if (!in) {
        return Error{path.string() + ": cannot be read"};
    }
    ObjLists lists;
    std::map<std::string, ObjMaterial> materials;
    ObjMaterial material;
    model.parts.push_back(objPart("default"));
    state.triangleTextures.emplace_back();
    std::string line;
    for (int number = 1; std::getline(in, line); ++number) {
        const std::string where = path.string() + ":" + std::to_string(number) + ": ";
        std::istringstream words(line.substr(0, line.find('#')));
        std::string keyword;
        if (!(words >> keyword)) {
            continue;
        }
        if (keyword == "v" || keyword == "vn") {
            glm::vec3 v;
            if (!(words >> v.x >> v.y >> v.z)) {
                return Error{where + "expected three numbers after '" + keyword + "'"};
            }
            (keyword == "v" ? lists.positions : lists.normals).push_back(v);
        } else if (keyword == "vt") {
            glm::vec2 uv;
            if (!(words >> uv.x >> uv.y)) {
                return Error{where + "expected two numbers after 'vt'"};
            }
            lists.uvs.emplace_back(uv.x, 1.0f - uv.y);  // OBJ's v runs up from the last row
        } else if (keyword == "o" || keyword == "g") {
            std::string name;
            words >> name;
            if (!model.parts.back().geometry.empty() || model.parts.back().name != "default") {
                model.parts.push_back(objPart(name));
                state.triangleTextures.emplace_back();
            } else {
                model.parts.back().name = name;
            }
        } else if (keyword == "mtllib") {
            std::string file;
            words >> file;
            Result<std::map<std::string, ObjMaterial>> read =
                readMtl(path.parent_path() / file, model, state);
            if (!read) {
                return read.error();
            }
            materials = std::move(read.value());
        } else if (keyword == "usemtl") {
            std::string name;
            words >> name;
            const auto found = materials.find(name);
            material = found != materials.end() ? found->second : ObjMaterial{};
        } else if (keyword == "f") {
            if (Status status = readFace(words, where, lists, material, model.parts.back().geometry,
                                         state.triangleTextures.back());
                !status) {
                return status;
            }
        }
    }
    return Status::success();
}

// The triangles of `geometry` listed in `triangles`, with only the vertices they use.
MeshGeometry subset(const MeshGeometry& geometry, const std::vector<std::size_t>& triangles) {
    MeshGeometry out;
    std::map<std::uint32_t, std::uint32_t> remap;
    for (const std::size_t t : triangles) {
        for (int k = 0; k < 3; ++k) {
            const std::uint32_t index = geometry.indices[3 * t + std::size_t(k)];
            auto [found, added] = remap.emplace(index, std::uint32_t(out.vertices.size()));
            if (added) {
                out.vertices.push_back(geometry.vertices[index]);
            }
            out.indices.push_back(found->second);
        }
    }
    return out;
}

// One texture per part (MeshModel::textures): a part's triangles of its first texture stay,
// those of every other texture go to a child part "<name>#<k>" with the identity transform.
void splitByTexture(MeshModel& model, const ImportState& state) {
    const std::size_t original = model.parts.size();
    for (std::size_t p = 0; p < original; ++p) {
        const std::vector<int>& textures = state.triangleTextures[p];
        std::vector<int> order;  // the part's textures by first use
        for (const int texture : textures) {
            if (std::find(order.begin(), order.end(), texture) == order.end()) {
                order.push_back(texture);
            }
        }
        if (order.empty()) {
            continue;
        }
        model.parts[p].texture = order.front();
        if (order.size() == 1) {
            continue;
        }
        const MeshGeometry whole = model.parts[p].geometry;
        for (std::size_t k = 0; k < order.size(); ++k) {
            std::vector<std::size_t> triangles;
            for (std::size_t t = 0; t < textures.size(); ++t) {
                if (textures[t] == order[k]) {
                    triangles.push_back(t);
                }
            }
            if (k == 0) {
                model.parts[p].geometry = subset(whole, triangles);
                continue;
            }
            ModelPart child;
            child.name = model.parts[p].name + "#" + std::to_string(k);
            child.parent = int(p);
            child.axis = model.parts[p].axis;
            child.geometry = subset(whole, triangles);
            child.texture = order[k];
            model.parts.push_back(std::move(child));
        }
    }
}

void computeBounds(MeshModel& model) {
    const std::vector<glm::dmat4> transforms = model.partTransforms({});
    glm::dvec3 low(std::numeric_limits<double>::infinity()), high(-low);
    for (std::size_t p = 0; p < model.parts.size(); ++p) {
        for (const MeshVertex& v : model.parts[p].geometry.vertices) {
            const glm::dvec3 q(transforms[p] * glm::dvec4(glm::dvec3(v.position), 1.0));
            low = glm::min(low, q);
            high = glm::max(high, q);
        }
    }
    model.boundsCenter = 0.5 * (low + high);
    // Articulated parts turn, so the sphere holds every vertex at its farthest reach: a
    // radius about the centre of the unarticulated box plus each part's own extent.
    double radius = 0.5 * glm::length(high - low);
    for (std::size_t p = 0; p < model.parts.size(); ++p) {
        const glm::dvec3 pivot(transforms[p][3]);
        for (const MeshVertex& v : model.parts[p].geometry.vertices) {
            const double reach = glm::length(glm::dmat3(transforms[p]) * glm::dvec3(v.position));
            radius = std::max(radius, glm::length(pivot - model.boundsCenter) + reach);
        }
    }
    model.boundsRadius = radius;
}

}  // namespace

Result<std::shared_ptr<const MeshModel>> importModel(const std::filesystem::path& file) {
    std::error_code error;
    if (!std::filesystem::is_regular_file(file, error)) {
        return Error{file.string() + ": no such model file"};
    }
    std::string extension = file.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    auto model = std::make_shared<MeshModel>();
    model->file = file.string();
    Status status = Status::success();
    ImportState state;
    if (extension == ".gltf" || extension == ".glb") {
        status = readGltf(file, extension == ".glb", *model, state);
    } else if (extension == ".obj") {
        status = readObj(file, *model, state);
    } else {
        return Error{file.string() + ": unknown model format '" + extension +
                     "' (.gltf, .glb or .obj)"};
    }
    if (!status) {
        return status.error();
    }
    if (model->triangleCount() == 0) {
        return Error{file.string() + ": the model has no triangles"};
    }
    splitByTexture(*model, state);
    computeBounds(*model);
    for (ModelPart& part : model->parts)
        part.levels = simplifyLevels(part.geometry);  // levels of detail (MeshSimplifier)
    return std::shared_ptr<const MeshModel>(model);
}

}  // namespace sylva
