// BuildingExtruder: one building's triangles from its footprint — walls from the lowest
// terrain point up to the eaves, and a flat, gable, hip or pyramid roof above them.
//
// The footprint is given in a local east/north plane in metres around the building's
// reference point (LocalPlane); every vertex is mapped back to latitude/longitude and
// then to ECEF with its exact height, so the heights of eaves and roof are exact
// whatever the plane's small-angle error (about d²/R, 1.5 mm at 100 m) does to
// positions. Faces are flat-shaded (normals from the ECEF triangle), counter-clockwise
// seen from outside.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "FootprintTriangulator.h"
#include "sylva/core/base/Result.h"
#include "sylva/core/sources/objects/MeshTile.h"

namespace sylva {

enum class RoofKind { Flat, Gable, Hip, Pyramid };

// The tangent plane approximation around (latitude, longitude): x east, y north, metres.
class LocalPlane {
public:
    LocalPlane(double latitude, double longitude);
    glm::dvec2 toLocal(const glm::dvec2& longitudeLatitude) const;
    glm::dvec2 toLongitudeLatitude(const glm::dvec2& local) const;

private:
    double latitude_, longitude_, eastMetres_, northMetres_;  // metres per radian
};

struct BuildingShape {
    std::vector<Ring> rings;  // open rings in the local plane: outer (CCW) first, holes CW
    double bottom = 0.0;      // bottom of the walls, metres above the ellipsoid
    double eaves = 0.0;       // top of the walls
    RoofKind roof = RoofKind::Flat;
    double pitch = 0.0;                                              // radians
    std::uint32_t wallColor = 0xffffffffu, roofColor = 0xffffffffu;  // packed sRGB8
};

class BuildingExtruder {
public:
    // Appends the building to `out` (positions relative to `origin`, ECEF). Fails when the
    // roof cannot be triangulated (GEOS's message).
    Status append(const BuildingShape& shape, const LocalPlane& plane, const glm::dvec3& origin,
                  MeshGeometry& out);

    // The roof actually built for a shape: gable needs four corners and no holes, hip and
    // pyramid a convex outer ring without holes (hip on other than four corners: the
    // straight skeleton's roof, HipRoof); otherwise the next simpler roof.
    static RoofKind effectiveRoof(const BuildingShape& shape);

private:
    struct Writer;
    Status appendFlatRoof(const BuildingShape& shape, Writer& writer);
    FootprintTriangulator triangulator_;
};

}  // namespace sylva
