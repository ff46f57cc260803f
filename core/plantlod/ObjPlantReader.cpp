#include "ObjPlantReader.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <map>

#include "ImportedPlant.h"
#include "MtlReader.h"
#include "ObjTokens.h"

namespace sylva::plantimport {

namespace {

// One face corner: 1-based vertex, texture coordinate and normal indices (0: none).
using Corner = std::array<int, 3>;

class ObjReader {
public:
    explicit ObjReader(const std::filesystem::path& path) : path_(path) {}

    Status statement(const std::vector<std::string>& words, int number) {
        const std::string where = path_.string() + ":" + std::to_string(number) + ": ";
        const std::string& keyword = words[0];
        if (keyword == "v" || keyword == "vn") {
            glm::vec3 v;
            if (words.size() < 4 || !parseFloat(words[1], v.x) || !parseFloat(words[2], v.y) ||
                !parseFloat(words[3], v.z)) {
                return Error{where + keyword + " needs three numbers"};
            }
            (keyword == "v" ? positions_ : normals_).push_back(v);
        } else if (keyword == "vt") {
            glm::vec2 t;
            if (words.size() < 3 || !parseFloat(words[1], t.x) || !parseFloat(words[2], t.y)) {
                return Error{where + "vt needs two numbers"};
            }
            uvs_.push_back(t);
        } else if (keyword == "o" || keyword == "g") {
            group_ = words.size() > 1 ? words[1] : "";
        } else if (keyword == "usemtl") {
            if (words.size() < 2 || materialByName_.count(words[1]) == 0) {
                return Error{where + "unknown material '" + (words.size() > 1 ? words[1] : "") +
                             "'"};
            }
            material_ = materialByName_[words[1]];
        } else if (keyword == "mtllib") {
            return materialLibrary(words, where);
        } else if (keyword == "l" || keyword == "p") {
            return Error{where + "unsupported element '" + keyword +
                         "' (only triangles and polygons)"};
        } else if (keyword == "f") {
            return face(words, where);
        }
        return Status::success();
    }

    Result<PlantModel> finish(const PlantImportOptions& options) {
        for (ImportedMesh& entry : meshes_) {
            // Corners without normals got zero vectors: recompute the whole mesh's then.
            const bool missing =
                std::any_of(entry.mesh.normals.begin(), entry.mesh.normals.end(),
                            [](const glm::vec3& n) { return n == glm::vec3(0.0f); });
            if (missing) {
                entry.mesh.normals.clear();
            }
        }
        return assemblePlantModel(path_, std::move(meshes_), std::move(materials_), {}, options);
    }

private:
    Status materialLibrary(const std::vector<std::string>& words, const std::string& where) {
        const std::string name = mapFileName(words);
        const std::filesystem::path library = path_.parent_path() / name;
        std::error_code error;
        if (!std::filesystem::exists(library, error)) {
            return Error{where + "material library '" + name + "' not found"};
        }
        return readMtlLibrary(library, materials_, materialByName_);
    }

    // The mesh of the current group and material (made on its first face).
    std::size_t currentMesh() {
        auto [it, inserted] = meshByKey_.emplace(std::pair(group_, material_), meshes_.size());
        if (inserted) {
            ImportedMesh entry;
            entry.meshName = group_;
            entry.nodeName = group_;
            entry.mesh.name = group_;
            entry.mesh.material = material_;
            entry.materialName = material_ >= 0 ? materials_[std::size_t(material_)].name : "";
            meshes_.push_back(std::move(entry));
            corners_.emplace_back();
        }
        return it->second;
    }

    // `v`, `v/vt`, `v//vn` or `v/vt/vn`, negative indices counting back from the end.
    Result<Corner> parseCorner(const std::string& word, const std::string& where) const {
        static const std::array<const char*, 3> kinds = {"vertex", "texture coordinate", "normal"};
        const std::array<std::size_t, 3> sizes = {positions_.size(), uvs_.size(), normals_.size()};
        Corner corner = {0, 0, 0};
        std::size_t start = 0;
        for (std::size_t field = 0; field < 3; ++field) {
            const std::size_t slash = word.find('/', start);
            const std::string part =
                word.substr(start, slash == std::string::npos ? std::string::npos : slash - start);
            if (!part.empty()) {
                int value = 0;
                auto [ptr, ec] = std::from_chars(part.data(), part.data() + part.size(), value);
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
            if (slash == std::string::npos) {
                break;
            }
            start = slash + 1;
        }
        return corner;
    }

    // The mesh vertex of a corner, added on its first use in the mesh.
    std::uint32_t vertexOf(std::size_t meshIndex, const Corner& corner) {
        PlantMesh& mesh = meshes_[meshIndex].mesh;
        auto [it, isNew] =
            corners_[meshIndex].emplace(corner, std::uint32_t(mesh.positions.size()));
        if (isNew) {
            mesh.positions.push_back(toModelFrame(positions_[std::size_t(corner[0] - 1)]));
            // OBJ texture rows start at the bottom; PlantTexture rows at the top.
            const glm::vec2 uv = corner[1] > 0 ? uvs_[std::size_t(corner[1] - 1)] : glm::vec2(0.0f);
            mesh.uvs.emplace_back(uv.x, 1.0f - uv.y);
            mesh.normals.push_back(
                corner[2] > 0 ? toModelFrame(glm::normalize(normals_[std::size_t(corner[2] - 1)]))
                              : glm::vec3(0.0f));
        }
        return it->second;
    }

    // A polygon, fanned into triangles.
    Status face(const std::vector<std::string>& words, const std::string& where) {
        if (words.size() < 4) {
            return Error{where + "a face needs at least 3 vertices"};
        }
        const std::size_t meshIndex = currentMesh();
        std::vector<std::uint32_t> face;
        for (std::size_t w = 1; w < words.size(); ++w) {
            Result<Corner> corner = parseCorner(words[w], where);
            if (!corner) {
                return corner.error();
            }
            face.push_back(vertexOf(meshIndex, *corner));
        }
        std::vector<std::uint32_t>& indices = meshes_[meshIndex].mesh.indices;
        for (std::size_t k = 2; k < face.size(); ++k) {
            indices.insert(indices.end(), {face[0], face[k - 1], face[k]});
        }
        return Status::success();
    }

    const std::filesystem::path& path_;
    std::vector<glm::vec3> positions_;
    std::vector<glm::vec2> uvs_;
    std::vector<glm::vec3> normals_;
    std::vector<PlantMaterial> materials_;
    std::map<std::string, int> materialByName_;
    std::vector<ImportedMesh> meshes_;
    std::map<std::pair<std::string, int>, std::size_t> meshByKey_;
    std::vector<std::map<Corner, std::uint32_t>> corners_;  // per mesh
    std::string group_;
    int material_ = -1;
};

}  // namespace

Result<PlantModel> readObjPlant(const std::filesystem::path& path,
                                const PlantImportOptions& options) {
    Result<std::string> text = readWholeFile(path);
    if (!text) {
        return text.error();
    }
    ObjReader reader(path);
    if (Status read =
            forEachStatement(*text, [&](const std::vector<std::string>& words,
                                        int number) { return reader.statement(words, number); });
        !read) {
        return read.error();
    }
    return reader.finish(options);
}

}  // namespace sylva::plantimport
