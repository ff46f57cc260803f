// MeshSimplifier: levels of detail of an imported model part for drawing it small (issue
// 17): the part's triangles welded by position and simplified by OpenMesh's Decimater with
// the quadric error module (Garland & Heckbert 1997: collapse the edge whose merged vertex
// moves least in the quadric sense) and normal-flip protection, to about a quarter of the
// triangles per level. Each level records its geometric error: the largest distance of the
// original (welded) vertices from the simplified surface, measured brute force (every
// vertex up to 4,096, else an even sample), so the renderer can switch to a level when
// that error projects below half a pixel.
//
// Shading of a level: vertex normals are recomputed from the simplified faces (area
// weighted), so hard edges of the original soften — acceptable at the sizes a level is
// drawn at; colours and texture coordinates are the surviving vertices' own (a collapse
// keeps one endpoint; OpenMesh vertex properties). Vertices are welded by position and
// texture coordinates, so a texture seam (one position, two uvs) splits the mesh; the
// vertices along it are locked, so every level keeps the seam where the original has it.
// Faces OpenMesh cannot add (non-manifold edges after welding) are left out of the
// levels; the full-detail geometry keeps them.
//
// ModelImporter calls it for every part (public for its tests). Never fails: a part that
// cannot be reduced gets no levels.
#pragma once

#include <vector>

#include "sylva/core/sources/objects/MeshTile.h"

namespace sylva {

// Parts below this many triangles get no levels (the draw costs more than the triangles).
inline constexpr std::size_t kSimplifyMinimumTriangles = 256;

std::vector<SimplifiedGeometry> simplifyLevels(const MeshGeometry& geometry);

}  // namespace sylva
