#include "sylva/core/sources/objects/ModelImporter.h"

#include "sylva/core/sources/objects/MeshSimplifier.h"

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

// Accessor `index` as floats (`components` per element); checked against its buffer.
Result<std::vector<float>> accessorFloats(const std::string& file, const tinygltf::Model& gltf,
                                          int index, int components) {
    const std::string where = file + ": accessor " + std::to_string(index) + ": ";
    if (index < 0 || std::size_t(index) >= gltf.accessors.size()) {
        return Error{where + "does not exist"};
    }
    const tinygltf::Accessor& accessor = gltf.accessors[std::size_t(index)];
    if (accessor.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT ||
        tinygltf::GetNumComponentsInType(std::uint32_t(accessor.type)) != components) {
        return Error{where + "expected " + std::to_string(components) + " floats per element"};
    }
    if (accessor.bufferView < 0 || std::size_t(accessor.bufferView) >= gltf.bufferViews.size()) {
        return Error{where + "has no buffer view"};
    }
    const tinygltf::BufferView& view = gltf.bufferViews[std::size_t(accessor.bufferView)];
    const std::vector<unsigned char>& data = gltf.buffers.at(std::size_t(view.buffer)).data;
    const std::size_t element = std::size_t(components) * sizeof(float);
    const std::size_t stride = view.byteStride != 0 ? view.byteStride : element;
    const std::size_t start = view.byteOffset + accessor.byteOffset;
    if (accessor.count > 0 && start + (accessor.count - 1) * stride + element > data.size()) {
        return Error{where + "reaches beyond its buffer (truncated file?)"};
    }
    std::vector<float> out(accessor.count * std::size_t(components));
    for (std::size_t i = 0; i < accessor.count; ++i) {
        std::memcpy(out.data() + i * std::size_t(components), data.data() + start + i * stride,
                    element);
    }
    return out;
}

Result<std::vector<std::uint32_t>> accessorIndices(const std::string& file,
                                                   const tinygltf::Model& gltf, int index) {
    const std::string where = file + ": accessor " + std::to_string(index) + ": ";
    if (index < 0 || std::size_t(index) >= gltf.accessors.size()) {
        return Error{where + "does not exist"};
    }
    const tinygltf::Accessor& accessor = gltf.accessors[std::size_t(index)];
    const int size = tinygltf::GetComponentSizeInBytes(std::uint32_t(accessor.componentType));
    if (accessor.bufferView < 0 || std::size_t(accessor.bufferView) >= gltf.bufferViews.size() ||
        (size != 1 && size != 2 && size != 4)) {
        return Error{where + "is not an index accessor"};
    }
    const tinygltf::BufferView& view = gltf.bufferViews[std::size_t(accessor.bufferView)];
    const std::vector<unsigned char>& data = gltf.buffers.at(std::size_t(view.buffer)).data;
    const std::size_t stride = view.byteStride != 0 ? view.byteStride : std::size_t(size);
    const std::size_t start = view.byteOffset + accessor.byteOffset;
    if (accessor.count > 0 &&
        start + (accessor.count - 1) * stride + std::size_t(size) > data.size()) {
        return Error{where + "reaches beyond its buffer (truncated file?)"};
    }
    std::vector<std::uint32_t> out(accessor.count);
    for (std::size_t i = 0; i < accessor.count; ++i) {
        const unsigned char* p = data.data() + start + i * stride;
        if (size == 1) {
            out[i] = *p;
        } else if (size == 2) {
            std::uint16_t v;
            std::memcpy(&v, p, 2);
            out[i] = v;
        } else {
            std::memcpy(&out[i], p, 4);
        }
    }
    return out;
}

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

Status appendPrimitive(const std::string& file, const tinygltf::Model& gltf,
                       const tinygltf::Primitive& primitive, MeshGeometry& geometry) {
    if (primitive.mode != -1 && primitive.mode != TINYGLTF_MODE_TRIANGLES) {
        return Status::success();  // points and lines are not drawn
    }
    const auto position = primitive.attributes.find("POSITION");
    if (position == primitive.attributes.end()) {
        return Error{file + ": a mesh primitive has no POSITION"};
    }
    Result<std::vector<float>> positions = accessorFloats(file, gltf, position->second, 3);
    if (!positions) {
        return positions.error();
    }
    std::vector<float> normals;
    if (const auto normal = primitive.attributes.find("NORMAL");
        normal != primitive.attributes.end()) {
        Result<std::vector<float>> read = accessorFloats(file, gltf, normal->second, 3);
        if (!read) {
            return read.error();
        }
        normals = std::move(read.value());
    }
    const std::size_t count = positions.value().size() / 3;
    std::vector<std::uint32_t> indices;
    if (primitive.indices >= 0) {
        Result<std::vector<std::uint32_t>> read = accessorIndices(file, gltf, primitive.indices);
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
    }
    fillMissingNormals(geometry, firstVertex, firstIndex);
    return Status::success();
}

Status addNode(const std::string& file, const tinygltf::Model& gltf, int index, int parent,
               MeshModel& model, int depth) {
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
    if (node.mesh >= 0 && std::size_t(node.mesh) < gltf.meshes.size()) {
        for (const tinygltf::Primitive& primitive :
             gltf.meshes[std::size_t(node.mesh)].primitives) {
            if (Status status = appendPrimitive(file, gltf, primitive, part.geometry); !status) {
                return status;
            }
        }
    }
    model.parts.push_back(std::move(part));
    const int self = int(model.parts.size()) - 1;
    for (int child : node.children) {
        if (Status status = addNode(file, gltf, child, self, model, depth + 1); !status) {
            return status;
        }
    }
    return Status::success();
}

Status readGltf(const std::filesystem::path& path, bool binary, MeshModel& model) {
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
        if (Status status = addNode(path.string(), gltf, root, -1, model, 0); !status) {
            return status;
        }
    }
    return Status::success();
}

// ------------------------------------------------------------------------------- OBJ

std::map<std::string, std::uint32_t> readMtl(const std::filesystem::path& path) {
    std::map<std::string, std::uint32_t> colors;
    std::ifstream in(path);
    std::string line, current;
    while (std::getline(in, line)) {
        std::istringstream words(line);
        std::string keyword;
        words >> keyword;
        if (keyword == "newmtl") {
            words >> current;
        } else if (keyword == "Kd" && !current.empty()) {
            double r = 1, g = 1, b = 1;
            words >> r >> g >> b;
            colors[current] = packLinear({r, g, b});
        }
    }
    return colors;
}

Status readObj(const std::filesystem::path& path, MeshModel& model) {
    std::ifstream in(path);
    if (!in) {
        return Error{path.string() + ": cannot be read"};
    }
    std::vector<glm::vec3> positions, normals;
    std::map<std::string, std::uint32_t> materials;
    std::uint32_t color = 0xffffffffu;
    model.parts.push_back(ModelPart{"default", -1, glm::dmat4(1.0), {0, 0, 1}, {}, {}});
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
            (keyword == "v" ? positions : normals).push_back(v);
        } else if (keyword == "o" || keyword == "g") {
            std::string name;
            words >> name;
            if (!model.parts.back().geometry.empty() || model.parts.back().name != "default") {
                model.parts.push_back(ModelPart{name, -1, glm::dmat4(1.0), {0, 0, 1}, {}, {}});
            } else {
                model.parts.back().name = name;
            }
        } else if (keyword == "mtllib") {
            std::string file;
            words >> file;
            materials = readMtl(path.parent_path() / file);
        } else if (keyword == "usemtl") {
            std::string name;
            words >> name;
            const auto found = materials.find(name);
            color = found != materials.end() ? found->second : 0xffffffffu;
        } else if (keyword == "f") {
            MeshGeometry& geometry = model.parts.back().geometry;
            const std::size_t firstVertex = geometry.vertices.size();
            std::string corner;
            while (words >> corner) {
                int vi = 0, ni = 0;
                const std::size_t slash = corner.find('/');
                const std::size_t last = corner.rfind('/');
                try {
                    vi = std::stoi(corner.substr(0, slash));
                    if (slash != std::string::npos && last + 1 < corner.size() && last != slash) {
                        ni = std::stoi(corner.substr(last + 1));
                    }
                } catch (...) {
                    return Error{where + "bad face corner '" + corner + "'"};
                }
                const int v = vi < 0 ? int(positions.size()) + vi : vi - 1;
                const int n = ni < 0 ? int(normals.size()) + ni : ni - 1;
                if (v < 0 || std::size_t(v) >= positions.size() ||
                    (ni != 0 && (n < 0 || std::size_t(n) >= normals.size()))) {
                    return Error{where + "face corner '" + corner + "' refers to a missing vertex"};
                }
                geometry.vertices.push_back(
                    MeshVertex{positions[std::size_t(v)],
                               ni != 0 ? normals[std::size_t(n)] : glm::vec3(0.0f), color});
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
            }
            fillMissingNormals(geometry, firstVertex, firstIndex);
        }
    }
    return Status::success();
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
    if (extension == ".gltf" || extension == ".glb") {
        status = readGltf(file, extension == ".glb", *model);
    } else if (extension == ".obj") {
        status = readObj(file, *model);
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
    computeBounds(*model);
    for (ModelPart& part : model->parts)
        part.levels = simplifyLevels(part.geometry);  // levels of detail (MeshSimplifier)
    return std::shared_ptr<const MeshModel>(model);
}

}  // namespace sylva
