// PlantGltfWriter: writes a PlantModel as glTF 2.0, either .gltf (JSON with the buffer
// and images embedded as base64 data URIs) or .glb (binary, images in buffer views).
// One glTF mesh per PlantMesh (one triangle primitive, POSITION/NORMAL/TEXCOORD_0),
// materials with alphaMode MASK for alpha-masked ones, textures as PNG, and the branch
// skeleton in asset.extras.sylva_skeleton = [{start, end, startRadius, endRadius,
// parent}, ...] in the file's frame (glTF +Y up: model (x, y, z) → file (x, z, −y)).
//
// Output is deterministic: the same model gives the same bytes. Files are written
// atomically (temporary file in the target folder, then rename). Errors name the path.
#pragma once

#include <filesystem>
#include <string>

#include "sylva/core/base/Result.h"
#include "sylva/core/plantlod/PlantModel.h"

namespace sylva {

class PlantGltfWriter {
public:
    // The file's bytes; `binary` selects GLB. Fails on inconsistent meshes.
    static Result<std::string> encode(const PlantModel& model, bool binary);
    // Chooses GLB for a .glb extension, JSON for .gltf; other extensions are an error.
    static Status write(const PlantModel& model, const std::filesystem::path& path);
};

}  // namespace sylva
