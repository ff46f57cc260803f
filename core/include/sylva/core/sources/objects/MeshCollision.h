// MeshCollision: segments against the proposal's meshes on the CPU — the buildings' static
// triangles and every placed model part of a set of MeshTiles — for the viewer's walker
// (core/sources/objects/WalkerCollision: the surface under the feet, the wall ahead), so the walk
// meets exactly the geometry that is drawn.
//
// Faces. A triangle is hit only from its front (MeshGeometry: counter-clockwise seen from
// outside; under a mirroring placement the model's outside stays the outside): walls stop
// a walker coming from outside, roofs carry one from above, and a camera placed inside a
// building can walk out through its walls.
//
// Cost. Static triangles are looked up through a grid over each tile's local east/north
// plane (cells of at least 2 m, at most 128 x 128 a tile), built the first time a segment
// reaches the tile's bounding sphere and kept while the tile stays in the set; model
// placements are culled by their bounding spheres and tested part by part at full detail.
// Tests run in double relative to the tile's origin (float offsets, ~0.1 mm).
//
// Not thread-safe: indexes are built lazily inside the const queries (one viewer thread).
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "sylva/core/sources/objects/MeshTile.h"

namespace sylva {

struct MeshHit {
    double fraction = 1.0;   // along the segment from its start, [0, 1]
    glm::dvec3 normal{0.0};  // ECEF unit normal of the face hit (its front faces the start)
};

class MeshCollision {
public:
    MeshCollision();
    ~MeshCollision();
    MeshCollision(MeshCollision&&) noexcept;
    MeshCollision& operator=(MeshCollision&&) noexcept;

    // The tiles searched from now on (shared with the renderer, read only). Indexes of
    // tiles already in the set are kept; those of tiles no longer in it are dropped.
    void setTiles(const std::vector<std::shared_ptr<const MeshTile>>& tiles);
    bool empty() const { return tiles_.empty(); }

    // The first front face crossed by the segment from `start` to `end` (ECEF metres), or
    // nothing. A degenerate segment (start == end) hits nothing.
    std::optional<MeshHit> firstHit(const glm::dvec3& start, const glm::dvec3& end) const;

private:
    struct TileIndex;
    // The index of `tile` (built on first use).
    const TileIndex& indexOf(const std::shared_ptr<const MeshTile>& tile) const;
    std::vector<std::shared_ptr<const MeshTile>> tiles_;
    mutable std::map<const MeshTile*, std::unique_ptr<TileIndex>> indexes_;
};

}  // namespace sylva
