// GltfPlantReader: a glTF 2.0 plant model (.gltf with embedded or external buffers and
// images, .glb) through tinygltf, for PlantImporter. The container, the JSON, the
// required extensions and the referenced files are checked first with our own messages
// (tinygltf's are not stable text); then materials (base colour factor and texture, alpha
// mode), the default scene's meshes with accumulated node transforms (triangle lists,
// strips and fans; mirrored transforms keep the winding), and the skeleton extras
// (GltfSkeleton). Errors start with the file path.
#pragma once

#include <filesystem>

#include "sylva/core/base/Result.h"
#include "sylva/core/plantlod/PlantImporter.h"
#include "sylva/core/plantlod/PlantModel.h"

namespace sylva::plantimport {

Result<PlantModel> readGltfPlant(const std::filesystem::path& path,
                                 const PlantImportOptions& options);

}  // namespace sylva::plantimport
