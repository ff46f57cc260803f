#include "sylva/core/analysis/ProposalReach.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "sylva/core/sources/objects/MeshTile.h"

namespace sylva {
namespace {

constexpr double kTurn = 2.0 * std::numbers::pi;

// East/north metres of `ecef`'s foot on the ellipsoid in the tangent plane at `origin`.
struct Plane {
    glm::dvec3 origin;
    glm::dvec3 east, north;

    glm::dvec2 of(const glm::dvec3& ecef) const {
        Geodetic foot = Ellipsoid::toGeodetic(ecef);
        foot.height = 0.0;
        const glm::dvec3 d = Ellipsoid::toEcef(foot) - origin;
        return {glm::dot(d, east), glm::dot(d, north)};
    }
};

// Distance from the origin to segment ab (plane coordinates).
double distanceToSegment(const glm::dvec2& a, const glm::dvec2& b) {
    const glm::dvec2 ab = b - a;
    const double length2 = glm::dot(ab, ab);
    const double t = length2 > 0.0 ? std::clamp(-glm::dot(a, ab) / length2, 0.0, 1.0) : 0.0;
    return glm::length(a + t * ab);
}

double bearingOf(const glm::dvec2& p) {
    const double bearing = std::atan2(p.x, p.y);
    return bearing < 0.0 ? bearing + kTurn : bearing;
}

// An arc of bearings: from `start` clockwise over `length` radians.
struct Arc {
    double start = 0.0;
    double length = 0.0;
};

// The arc a segment covers seen from the origin: the shorter way between its ends'
// bearings (half a turn when the origin lies on it).
Arc arcOf(const glm::dvec2& a, const glm::dvec2& b) {
    const double from = bearingOf(a);
    const double turn = std::remainder(bearingOf(b) - from, kTurn);  // (-π, π]
    return turn >= 0.0 ? Arc{from, turn} : Arc{bearingOf(b), -turn};
}

// The largest arc no part covers (start = the clockwise end of the covered arc before it,
// i.e. where the proposal's extent begins after the gap); nullopt when all is covered.
std::optional<Arc> largestGap(std::vector<Arc> arcs) {
    std::sort(arcs.begin(), arcs.end(), [](Arc a, Arc b) { return a.start < b.start; });
    double reach = -INFINITY;
    for (const Arc& arc : arcs) {
        reach = std::max(reach, arc.start + arc.length);
    }
    reach -= kTurn;  // what the arcs reaching past north cover at the start of the turn
    std::optional<Arc> best;
    for (const Arc& arc : arcs) {
        if (arc.start > reach && (!best || arc.start - reach > best->length)) {
            best = Arc{arc.start, arc.start - reach};
        }
        reach = std::max(reach, arc.start + arc.length);
    }
    return best;
}

}  // namespace

std::optional<ProposalReach> ProposalReach::measure(const Geodetic& viewpoint,
                                                    const ProposalParts& parts) {
    if (parts.empty()) {
        return std::nullopt;
    }
    const glm::dmat3 frame = Ellipsoid::localFrame(viewpoint.latitude, viewpoint.longitude);
    const Plane plane{Ellipsoid::toEcef({viewpoint.latitude, viewpoint.longitude, 0.0}), frame[0],
                      frame[1]};
    ProposalReach reach;
    reach.nearestDistance = INFINITY;
    std::vector<Arc> arcs;
    for (const glm::dvec3& point : parts.points) {
        const glm::dvec2 p = plane.of(point);
        reach.nearestDistance = std::min(reach.nearestDistance, glm::length(p));
        reach.farthestDistance = std::max(reach.farthestDistance, glm::length(p));
        arcs.push_back({bearingOf(p), 0.0});
    }
    for (const auto& [ecefA, ecefB] : parts.segments) {
        const glm::dvec2 a = plane.of(ecefA), b = plane.of(ecefB);
        reach.nearestDistance = std::min(reach.nearestDistance, distanceToSegment(a, b));
        reach.farthestDistance =
            std::max(reach.farthestDistance, std::max(glm::length(a), glm::length(b)));
        arcs.push_back(arcOf(a, b));
    }
    const std::optional<Arc> gap = largestGap(std::move(arcs));
    reach.horizontalExtent = gap ? kTurn - gap->length : kTurn;
    reach.leftBearing = gap ? std::fmod(gap->start, kTurn) : 0.0;
    reach.rightBearing = std::fmod(reach.leftBearing + reach.horizontalExtent, kTurn);
    return reach;
}

Result<ProposalParts> ProposalReach::partsOf(const std::vector<const MeshSource*>& sources,
                                             TileProvider& provider) {
    ProposalParts parts;
    for (const MeshSource* source : sources) {
        Result<GeographicBounds> bounds = source->bounds();
        if (!bounds) {
            return bounds.error();
        }
        const TileKey first = MeshSource::keyOf({bounds->west, bounds->north});
        const TileKey last = MeshSource::keyOf({bounds->east, bounds->south});
        for (int y = first.y; y <= last.y; ++y) {
            for (int x = first.x; x <= last.x; ++x) {
                auto tile = source->tile(TileKey{MeshSource::kTileLevel, 0, x, y}, provider);
                if (!tile) {
                    return tile.error();
                }
                const MeshTile& meshes = **tile;
                for (const ModelPlacement& placement : meshes.placements) {
                    parts.points.push_back(placement.position);
                    parts.pointIds.push_back(placement.featureId);
                }
                const std::vector<MeshVertex>& vertices = meshes.geometry.vertices;
                const std::vector<std::uint32_t>& indices = meshes.geometry.indices;
                auto at = [&](std::uint32_t i) {
                    return meshes.origin + glm::dvec3(vertices[i].position);
                };
                for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
                    for (int e = 0; e < 3; ++e) {
                        parts.segments.emplace_back(at(indices[t + e]),
                                                    at(indices[t + (e + 1) % 3]));
                    }
                }
            }
        }
    }
    return parts;
}

}  // namespace sylva
