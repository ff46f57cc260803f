// PlantImporter: reads a plant model file into a PlantModel (seed 001 §3.3: leaves and
// branches imported separately; the branch structure "either given by the modelling
// system ... or reconstructed from the source model").
//
// Formats: glTF 2.0 (.gltf with embedded or external buffers and images, .glb) through
// tinygltf (GltfPlantReader, GltfAccessors, GltfSkeleton), and Wavefront OBJ with its .mtl
// (Kd, d/Tr, map_Kd, map_d) through a small reader of our own (ObjPlantReader, MtlReader;
// OpenMesh 9.0's OBJ reader knows map_Kd but not map_d, builds a half-edge mesh that
// rejects non-manifold leaf geometry, and reports bad indices only to its log stream, so
// located error messages would be impossible). Both hand their meshes to the common rest
// of the import (ImportedPlant: the rules below, normals, skeleton).
//
// Frames: both formats are taken as +Y up (glTF by specification, OBJ by the common
// convention) and converted to the model frame, +Z up: file (x, y, z) → (x, −z, y).
// Node transforms are applied. Lengths are taken as metres.
//
// Leaves vs branches, first rule that applies per mesh (docs/plants.md):
//   1. the sidecar `<model stem>.plant.json` next to the file (PlantSidecar): {"parts":
//      {NAME: "leaf" | "branch"}}, NAME matching a material, mesh or node name;
//   2. an alpha-masked or blended material, or a base texture with alpha < 0.5 somewhere → leaf;
//   3. a material, mesh or node name containing leaf, leaves, needle, foliage, frond,
//      blatt, laub, nadel, feuille → leaf;
//   4. otherwise branch.
// Skeleton: asset.extras.sylva_skeleton (or the root node's extras) when present,
// otherwise reconstructed from the branch meshes (SkeletonReconstructor).
//
// Errors (Result): every message starts with the file path and names the problem:
// missing file, corrupt or truncated glTF, invalid JSON, missing buffer/image file,
// unsupported features (Draco and other required extensions, sparse accessors,
// points/lines), OBJ syntax and index errors with the line number, a model without
// leaves or without branches.
#pragma once

#include <filesystem>

#include "sylva/core/base/Result.h"
#include "sylva/core/plantlod/PlantModel.h"

namespace sylva {

struct PlantImportOptions {
    // When false the file's skeleton extras are ignored and the skeleton is always
    // reconstructed from the branch meshes (tests and comparisons).
    bool useFileSkeleton = true;
    // Require both parts (the LoD builder needs leaves and branches).
    bool requireLeavesAndBranches = true;
};

class PlantImporter {
public:
    static Result<PlantModel> import(const std::filesystem::path& path,
                                     const PlantImportOptions& options = {});
};

}  // namespace sylva
