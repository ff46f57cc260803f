// MtlReader: a Wavefront material library (.mtl) for ObjPlantReader: `newmtl`, `Kd`,
// `d` / `Tr` (opacity), `map_Kd` and `map_d` (options before the file name skipped);
// other statements are ignored. `map_d` becomes the alpha of the base texture (from the
// map's alpha channel when it has one, else its grey) and makes the material
// alpha-masked. Errors name the library, the line and the problem.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "sylva/core/base/Result.h"
#include "sylva/core/plantlod/PlantModel.h"

namespace sylva::plantimport {

// Appends the library's materials to `materials` and their indices to `byName` (a later
// material of the same name wins).
Status readMtlLibrary(const std::filesystem::path& library, std::vector<PlantMaterial>& materials,
                      std::map<std::string, int>& byName);

}  // namespace sylva::plantimport
