// FootprintTriangulator: roofs of buildings as triangles, by GEOS's constrained Delaunay
// triangulation of the footprint polygon (GEOSConstrainedDelaunayTriangulation, GEOS ≥ 3.10:
// every ring edge is kept, holes stay empty), and the validity check of footprints
// (GEOSisValidReason: self-intersections, rings touching, holes outside the shell).
//
// Why GEOS and not CGAL: the C API is small and stable, handles holes directly, and
// is already how GDAL (which reads the features) validates geometry; CGAL would add a
// large header-only dependency for the same triangulation.
//
// Coordinates are metres in a local east/north plane (the caller's), rings open (the
// first vertex not repeated), outer ring first. One object per thread (it owns a GEOS
// context handle).
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "sylva/core/base/Result.h"

namespace sylva {

using Ring = std::vector<glm::dvec2>;

class FootprintTriangulator {
public:
    FootprintTriangulator();
    ~FootprintTriangulator();
    FootprintTriangulator(const FootprintTriangulator&) = delete;
    FootprintTriangulator& operator=(const FootprintTriangulator&) = delete;

    // Empty when the polygon is valid, else GEOS's reason ("Self-intersection[x y]").
    std::string invalidReason(const std::vector<Ring>& rings);

    // The polygon's triangles, three corners each, counter-clockwise (seen from +z);
    // fails with GEOS's message when the triangulation fails.
    Result<std::vector<glm::dvec2>> triangulate(const std::vector<Ring>& rings);

private:
    void* context_;  // GEOSContextHandle_t
};

}  // namespace sylva
