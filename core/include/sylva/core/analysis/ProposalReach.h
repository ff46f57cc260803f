// ProposalReach: what a viewpoint record says about the proposal from its geometry (LI TGN
// 06/19 practice: "distance to the nearest part of the proposal and its horizontal extent
// in degrees"), for every render of a scenario with buildings or objects, visible or not
// (a photomontage also measures the visible part on its render: ProposalExtent).
//
// The proposal's parts: for `objects` sources every placed model's origin (a turbine's
// tower foot: turbine distances are stated to the tower), for `buildings` every triangle
// edge of the drawn geometry (the nearest point of a footprint lies on an edge, not only
// at a corner). Both are taken down to the ellipsoid along their normal and measured in
// the local east/north plane of the viewpoint's foot: a horizontal distance and bearings
// clockwise from true north. Against the geodesic (GeographicLib) that differs by about
// d³ / (6 R²): 3 cm at 20 km (tested).
//
// The horizontal extent is the smallest arc of bearings holding every part (the complement
// of the largest gap between them), so a proposal straddling north is not 360° wide; a
// viewpoint inside a building's footprint sees it over 360°.
//
// Failures (Result errors): a mesh source's own errors (its features, its model file).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "sylva/core/base/Result.h"
#include "sylva/core/geo/Ellipsoid.h"
#include "sylva/core/sources/objects/MeshSource.h"
#include "sylva/core/tiles/TileProvider.h"

namespace sylva {

// The proposal's parts in ECEF metres: points (placement origins) and segments (edges).
struct ProposalParts {
    std::vector<glm::dvec3> points;
    std::vector<std::int64_t> pointIds;  // the feature id of each point (-1: none), as points
    std::vector<std::pair<glm::dvec3, glm::dvec3>> segments;
    bool empty() const { return points.empty() && segments.empty(); }
};

struct ProposalReach {
    double nearestDistance = 0.0;   // metres, horizontal, to the nearest part
    double farthestDistance = 0.0;  // metres, horizontal, to the farthest point or vertex
    double leftBearing = 0.0;       // radians clockwise from north, [0, 2π): the arc's start
    double rightBearing = 0.0;      // ... and its end (clockwise from leftBearing)
    double horizontalExtent = 0.0;  // radians, [0, 2π]

    // nullopt without parts.
    static std::optional<ProposalReach> measure(const Geodetic& viewpoint,
                                                const ProposalParts& parts);
    // The parts of every tile of `sources` (their bounds' tiles of MeshSource::kTileLevel).
    static Result<ProposalParts> partsOf(const std::vector<const MeshSource*>& sources,
                                         TileProvider& provider);
};

}  // namespace sylva
