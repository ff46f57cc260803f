// Plant import (seed 001 §3.3): the file type picks the reader (GltfPlantReader,
// ObjPlantReader); both hand their meshes to assemblePlantModel (ImportedPlant.h) for
// the leaf/branch split (PlantSidecar first) and the skeleton.
#include "sylva/core/plantlod/PlantImporter.h"

#include <exception>

#include "GltfPlantReader.h"
#include "ImportedPlant.h"
#include "ObjPlantReader.h"

namespace sylva {

Result<PlantModel> PlantImporter::import(const std::filesystem::path& path,
                                         const PlantImportOptions& options) {
    std::error_code error;
    if (!std::filesystem::is_regular_file(path, error)) {
        return Error{path.string() + ": file not found"};
    }
    const std::string extension = plantimport::lowercase(path.extension().string());
    // Library exceptions (allocation, nlohmann) stop here, as errors naming the file.
    try {
        if (extension == ".gltf" || extension == ".glb") {
            return plantimport::readGltfPlant(path, options);
        }
        if (extension == ".obj") {
            return plantimport::readObjPlant(path, options);
        }
    } catch (const std::exception& e) {
        return Error{path.string() + ": cannot import: " + e.what()};
    }
    return Error{path.string() + ": unsupported plant file type '" + extension +
                 "' (use .gltf, .glb or .obj)"};
}

}  // namespace sylva
