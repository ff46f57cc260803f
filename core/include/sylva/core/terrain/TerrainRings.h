// TerrainRings: the static support geometry of the spherical geometry clipmap (seed
// 001 §5.3.4). Concentric rings on the view hemisphere around the viewer's nadir:
// the bearing is divided into `columns` fixed steps, and ring level i covers view
// angles (2^-(i+1) pi, 2^-i pi] with `ringsPerLevel` rings spaced by the factor
// 2^(-1/ringsPerLevel), so triangles keep about the same size on screen.
//
// Every level has the same topology, so one ring mesh serves all levels: a vertex
// stores its view angle for level 0 and the shader multiplies by 2^-i (exact in
// float, which keeps level borders bit-identical and crack-free). A fill disk closes
// the finest drawn level down to the nadir. The column at bearing 0 is duplicated
// (seam = +1 / -1) so texture coordinates can jump by 2 pi beyond the pole without
// smearing across a triangle (§5.4.4).
#pragma once

#include <cstdint>
#include <vector>

namespace sylva {

struct TerrainVertex {
    float viewAngle;   // radians, for level 0 (multiply by 2^-level)
    float blend;       // 0: this level's clipmap, 1: the next coarser one (outer border)
    float sinBearing;  // bearing clockwise from north (or south, see the renderer)
    float cosBearing;
    float seam;  // +1 first column, -1 duplicated last column, 0 otherwise
};

struct TerrainMesh {
    std::vector<TerrainVertex> vertices;
    std::vector<std::uint32_t> indices;  // triangles
};

class TerrainRings {
public:
    TerrainRings(int columns, int ringsPerLevel);

    int columns() const { return columns_; }
    int ringsPerLevel() const { return ringsPerLevel_; }
    // One level's rings, view angles from pi (outer) to pi/2 (inner) for level 0.
    const TerrainMesh& ringMesh() const { return ring_; }
    // The disk inside a level: pi/2 down to the nadir for level 0.
    const TerrainMesh& fillMesh() const { return fill_; }

    // A level blends into the next coarser one over its outer rings: fully coarse
    // in the outer kBlendStart of its rings (so its own clipmap is never needed at
    // the very border), then smoothly to its own level at kBlendEnd.
    static constexpr float kBlendStart = 0.1f;
    static constexpr float kBlendEnd = 0.5f;

private:
    void addRows(TerrainMesh& mesh, int firstRow, int lastRow, bool blend) const;

    int columns_;
    int ringsPerLevel_;
    TerrainMesh ring_;
    TerrainMesh fill_;
};

}  // namespace sylva
