// ImportedPlant: what the format readers of PlantImporter (GltfPlantReader,
// ObjPlantReader) hand over — meshes with the names that may decide their part,
// materials, and the file's skeleton if it has one — and the format-independent rest of
// the import: the leaf/branch split (PlantImporter.h, rules 1–4), missing normals, the
// leaves-and-branches requirement and the skeleton (from the file or reconstructed).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "sylva/core/base/Result.h"
#include "sylva/core/plantlod/PlantImporter.h"
#include "sylva/core/plantlod/PlantModel.h"

namespace sylva::plantimport {

// One primitive before classification: the names that may decide its part.
struct ImportedMesh {
    PlantMesh mesh;
    std::string materialName;
    std::string meshName;
    std::string nodeName;
};

// File frame (+Y up, glTF by specification, OBJ by convention) to model frame (+Z up).
inline glm::vec3 toModelFrame(const glm::vec3& v) {
    return {v.x, -v.z, v.y};
}

std::string lowercase(std::string text);

// Some texel with alpha < 0.5 (below 128).
bool textureHasAlpha(const PlantTexture& texture);

// The whole file; errors name the path ("file not found", "cannot read the file").
Result<std::string> readWholeFile(const std::filesystem::path& path);

// Classifies the meshes (the sidecar of `path` first), marks alpha-textured leaf
// materials alpha-masked, computes missing normals, drops empty meshes, checks the
// leaves-and-branches requirement and takes `skeleton`, or reconstructs one when it is
// empty. The model is named after the file's stem.
Result<PlantModel> assemblePlantModel(const std::filesystem::path& path,
                                      std::vector<ImportedMesh> meshes,
                                      std::vector<PlantMaterial> materials,
                                      std::vector<SkeletonSegment> skeleton,
                                      const PlantImportOptions& options);

}  // namespace sylva::plantimport
