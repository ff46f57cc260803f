// VisibleSets: approximate visible sets of a point-sampled plant per view direction
// (seed 000 ch. 3.2–3.3). Preprocessing: view directions on the unit sphere from a
// subdivided icosahedron (the thesis subdivides a tetrahedron; the icosahedron's cells are
// more uniform); for each direction the whole cloud is ID-rendered orthographically (each
// sample a disc of its radius, no antialiasing, nearest sample wins per pixel, CPU z-buffer
// instead of a frame-buffer read-back) and every sample covering at least one pixel is in
// the direction's set, its pixel count added to its contribution ("original" LOD
// estimation, §3.2.5: samples sorted by descending contribution, so a renderer draws a
// prefix when the plant is small on screen).
//
// Runtime (§3.3): the thesis combines the sets of the three nearest view directions. The
// directions are the vertices of a geodesic triangulation, so the three nearest ones of a
// direction are (nearly always) the corners of the spherical triangle holding it; each
// triangle ("cell") stores the union of its corners' sets, sorted by contribution, and an
// instance draws the set of the cell its view direction falls in — the same samples,
// without drawing the shared ones three times.
//
// Approximation (as in the thesis, §3.4 limitations): orthographic views at one image
// resolution, so a sample visible only from between the corner directions, or only in
// perspective up close, can be missing; tests bound the recall against a brute-force
// oracle. Frame: the point cloud's (model frame, metres).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "sylva/core/plantlod/PointCloudBuilder.h"

namespace sylva {

struct VisibleSetOptions {
    int subdivisions = 1;  // icosahedron subdivisions: 0 → 12 directions, 1 → 42, 2 → 162
    int resolution = 256;  // ID image pixels across the bounding sphere's diameter
    // Samples smaller than this many pixels are splatted at this size (the thesis renders
    // samples "larger than one pixel" for the LOD estimation).
    float minimumPixels = 1.0f;
    // Discs are ID-rendered at this fraction of their radius (< 1: smaller occluders keep
    // more samples, but gaps between the discs let hidden ones through; 1 measured best).
    float occluderScale = 1.0f;
};

class VisibleSets {
public:
    // Builds the sets of `cloud` (at least one point). Deterministic.
    static VisibleSets build(const PointCloud& cloud, const VisibleSetOptions& options = {});

    // The unit view directions (from the plant towards the viewer, model frame).
    const std::vector<glm::vec3>& directions() const { return directions_; }
    // Cells: spherical triangles of three direction indices, counter-clockwise seen from
    // outside the sphere.
    const std::vector<std::array<std::uint32_t, 3>>& cells() const { return cells_; }
    // Per direction: the visible samples, by descending contribution.
    const std::vector<std::vector<std::uint32_t>>& directionSets() const { return sets_; }
    // Per cell: the union of its corners' sets by descending contribution, concatenated
    // (cell c is cellPoints()[cellOffsets()[c] .. cellOffsets()[c + 1])).
    const std::vector<std::uint32_t>& cellOffsets() const { return cellOffsets_; }
    const std::vector<std::uint32_t>& cellPoints() const { return cellPoints_; }
    // Pixels each sample covered over all directions (its contribution).
    const std::vector<std::uint32_t>& contributions() const { return contributions_; }

    // The cell whose spherical triangle holds `direction` (any length > 0); on an edge the
    // lower index. Never fails: rounding that leaves a direction in no triangle falls back
    // to the cell whose corner directions are nearest on average.
    std::uint32_t cellOf(glm::vec3 direction) const;

    // The subdivided icosahedron (exposed for tests).
    static void geodesicSphere(int subdivisions, std::vector<glm::vec3>& directions,
                               std::vector<std::array<std::uint32_t, 3>>& cells);

private:
    std::vector<glm::vec3> directions_;
    std::vector<std::array<std::uint32_t, 3>> cells_;
    std::vector<std::vector<std::uint32_t>> sets_;
    std::vector<std::uint32_t> cellOffsets_, cellPoints_;
    std::vector<std::uint32_t> contributions_;
};

}  // namespace sylva
