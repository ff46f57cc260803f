// ObjPlantReader: a Wavefront OBJ plant model with its MTL libraries (MtlReader), for
// PlantImporter: `v vt vn f o g usemtl mtllib`; polygons fanned into triangles; negative
// (relative) indices; one mesh per (group, material). OpenMesh 9.0's reader is not used:
// it knows no `map_d`, builds a half-edge mesh that rejects non-manifold leaf geometry and
// reports bad indices only to its log, so located messages would be impossible.
// Errors name the file, the line and the problem.
#pragma once

#include <filesystem>

#include "sylva/core/base/Result.h"
#include "sylva/core/plantlod/PlantImporter.h"
#include "sylva/core/plantlod/PlantModel.h"

namespace sylva::plantimport {

Result<PlantModel> readObjPlant(const std::filesystem::path& path,
                                const PlantImportOptions& options);

}  // namespace sylva::plantimport
