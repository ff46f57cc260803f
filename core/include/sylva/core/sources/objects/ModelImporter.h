// ModelImporter: a 3D model for the `objects` source — glTF 2.0 (.gltf with its buffers,
// .glb; read by tinygltf) or Wavefront OBJ (own reader: v, vt, vn, f, o/g, usemtl with
// the Kd colours and map_Kd textures of its mtllib) — as a MeshModel of named parts.
//
// glTF: every node of the default scene (else every root) becomes a part with its name,
// parent and local transform (matrix or TRS); its mesh's TRIANGLES primitives give the
// triangles, coloured by the material's baseColorFactor (textures are not read). The
// root transform turns glTF's +Y up / +Z forward into the model frame's +Z up / +Y
// forward. OBJ: one part per `o` or `g` name (identity transforms, +Z up as written).
// Missing normals are computed per face.
//
// Fails with "<file>: <reason>": the file is missing, has an unknown extension, is
// truncated or malformed (tinygltf's or the OBJ line's message), has no triangles, or a
// texture cannot be read or lacks its texture coordinates.
#pragma once

#include <filesystem>
#include <memory>

#include "sylva/core/base/Result.h"
#include "sylva/core/sources/objects/MeshTile.h"

namespace sylva {

Result<std::shared_ptr<const MeshModel>> importModel(const std::filesystem::path& file);

}  // namespace sylva
