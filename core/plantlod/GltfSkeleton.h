// GltfSkeleton: the branch skeleton a glTF file may carry (written by PlantGltfWriter):
// `asset.extras.sylva_skeleton`, or else the first root node's `extras.sylva_skeleton`, an
// array of {start: [x, y, z], end: [x, y, z], startRadius, endRadius, parent} in the file
// frame (+Y up, metres), parent −1 or the index of another segment, the parents a forest.
#pragma once

#include <filesystem>
#include <vector>

#include <nlohmann/json.hpp>

#include "sylva/core/base/Result.h"
#include "sylva/core/plantlod/PlantModel.h"

namespace sylva::plantimport {

// The skeleton in the model frame, or none when the file has no `sylva_skeleton`.
// `roots` are the nodes of the scene. Errors name the file, the JSON path and the segment.
Result<std::vector<SkeletonSegment>> readGltfSkeleton(const std::filesystem::path& path,
                                                      const nlohmann::json& json,
                                                      const std::vector<int>& roots);

}  // namespace sylva::plantimport
