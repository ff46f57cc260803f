// The format-independent half of plant import (seed 001 §3.3): leaves and branches
// apart, and the branch skeleton "either given by the modelling system ... or
// reconstructed from the source model" (SkeletonReconstructor).
#include "ImportedPlant.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <fstream>
#include <sstream>

#include "sylva/core/plantlod/PlantSidecar.h"
#include "sylva/core/plantlod/SkeletonReconstructor.h"

namespace sylva::plantimport {

namespace {

bool hasLeafName(const std::string& name) {
    static const std::array<const char*, 9> words = {
        "leaf", "leaves", "needle", "foliage", "frond", "blatt", "laub", "nadel", "feuille"};
    const std::string lower = lowercase(name);
    return std::any_of(words.begin(), words.end(),
                       [&](const char* word) { return lower.find(word) != std::string::npos; });
}

// The first rule that applies (PlantImporter.h): sidecar, alpha, leaf-like name, branch.
PlantPart classify(const ImportedMesh& imported, const std::vector<PlantMaterial>& materials,
                   const PlantSidecar& sidecar) {
    for (const std::string* name :
         {&imported.materialName, &imported.meshName, &imported.nodeName}) {
        if (std::optional<PlantPart> part = sidecar.partOf(*name)) {
            return *part;
        }
    }
    if (imported.mesh.material >= 0) {
        const PlantMaterial& material = materials[std::size_t(imported.mesh.material)];
        if (material.alphaMasked || material.baseColor.a < 1.0f ||
            textureHasAlpha(material.baseColorTexture)) {
            return PlantPart::Leaf;
        }
    }
    if (hasLeafName(imported.materialName) || hasLeafName(imported.meshName) ||
        hasLeafName(imported.nodeName)) {
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

Status checkLeavesAndBranches(const std::filesystem::path& path, const PlantModel& model) {
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
    return Status::success();
}

}  // namespace

std::string lowercase(std::string text) {
    for (char& c : text) {
        c = char(std::tolower(static_cast<unsigned char>(c)));
    }
    return text;
}

bool textureHasAlpha(const PlantTexture& texture) {
    for (std::size_t i = 3; i < texture.rgba.size(); i += 4) {
        if (texture.rgba[i] < 128) {
            return true;
        }
    }
    return false;
}

Result<std::string> readWholeFile(const std::filesystem::path& path) {
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

Result<PlantModel> assemblePlantModel(const std::filesystem::path& path,
                                      std::vector<ImportedMesh> meshes,
                                      std::vector<PlantMaterial> materials,
                                      std::vector<SkeletonSegment> skeleton,
                                      const PlantImportOptions& options) {
    Result<PlantSidecar> sidecar = PlantSidecar::readFor(path);
    if (!sidecar) {
        return sidecar.error();
    }
    PlantModel model;
    model.name = path.stem().string();
    for (ImportedMesh& entry : meshes) {
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
        if (Status both = checkLeavesAndBranches(path, model); !both) {
            return both.error();
        }
    }
    model.skeleton =
        skeleton.empty() ? SkeletonReconstructor::reconstruct(model.meshes) : std::move(skeleton);
    return model;
}

}  // namespace sylva::plantimport
