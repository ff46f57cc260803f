#include "sylva/core/sources/objects/WalkerCollision.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "sylva/core/geo/Ellipsoid.h"
#include "sylva/core/scene/CameraNavigation.h"

namespace sylva {

namespace {

// Probes reach this much farther than the move plus the radius over the cosine of the
// incidence, so a wall met at up to ~75° from its normal still keeps the body `radius`
// off (measured perpendicular to it), not only along the move.
constexpr double kMinimumIncidenceCosine = 0.25;

// How far a walker can go before its body touches a wall, and that wall's normal.
struct Clearance {
    double metres = 0.0;
    bool blocked = false;
    glm::dvec3 normal{0.0};  // horizontal unit normal of the wall met (when blocked)
};

// Horizontal probes from `feet` (geodetic: the feet's position) along unit `direction`
// (ECEF, horizontal) at knee, waist and eye height: the distance the body may move, up to
// `length`, keeping `radius` perpendicular to the nearest wall met.
Clearance clearanceAlong(const MeshCollision& meshes, const Geodetic& feet,
                         const glm::dvec3& direction, double length, const WalkerBody& body) {
    const glm::dvec3 up = Ellipsoid::surfaceNormal(feet.latitude, feet.longitude);
    const double reach = length + body.radius / kMinimumIncidenceCosine;
    const std::array<double, 3> heights = {body.stepHeight + 0.05,
                                           (body.stepHeight + body.eyeHeight) / 2, body.eyeHeight};
    Clearance clearance;
    clearance.metres = length;
    for (const double height : heights) {
        const Geodetic probe{feet.latitude, feet.longitude, feet.height + height};
        const glm::dvec3 start = Ellipsoid::toEcef(probe);
        const std::optional<MeshHit> hit = meshes.firstHit(start, start + direction * reach);
        if (!hit) {
            continue;
        }
        glm::dvec3 normal = hit->normal - up * glm::dot(hit->normal, up);
        if (glm::length(normal) < 1e-6) {
            continue;  // a floor or ceiling along the probe: not a wall
        }
        normal = glm::normalize(normal);
        // The wall is `hit` metres ahead along the move; the body stops where its distance
        // perpendicular to the wall is the radius.
        const double incidence = std::max(-glm::dot(direction, normal), kMinimumIncidenceCosine);
        const double allowed = std::max(hit->fraction * reach - body.radius / incidence, 0.0);
        if (allowed < clearance.metres) {
            clearance = {allowed, true, normal};
        }
    }
    return clearance;
}

// `feet` moved `metres` along the horizontal unit `direction`, at the same height.
Geodetic movedAlong(const Geodetic& feet, const glm::dvec3& direction, double metres) {
    Geodetic moved = Ellipsoid::toGeodetic(Ellipsoid::toEcef(feet) + direction * metres);
    moved.height = feet.height;
    return moved;
}

}  // namespace

double WalkerCollision::standingHeight(const MeshCollision& meshes, double latitude,
                                       double longitude, double feetHeight, double groundHeight,
                                       const WalkerBody& body) {
    const double top = feetHeight + body.stepHeight;
    if (meshes.empty() || top <= groundHeight) {
        return groundHeight;
    }
    // Down from the highest reachable point to the terrain: the first face from above is
    // the surface stood on (roofs and floors face up).
    const glm::dvec3 start = Ellipsoid::toEcef(Geodetic{latitude, longitude, top});
    const glm::dvec3 end = Ellipsoid::toEcef(Geodetic{latitude, longitude, groundHeight});
    const std::optional<MeshHit> hit = meshes.firstHit(start, end);
    if (!hit) {
        return groundHeight;
    }
    return std::max(top - hit->fraction * (top - groundHeight), groundHeight);
}

Camera WalkerCollision::step(const MeshCollision& meshes, const Camera& from, const Camera& to,
                             const WalkerBody& body) {
    if (meshes.empty()) {
        return to;
    }
    const glm::dvec3 up = Ellipsoid::surfaceNormal(from.geodetic.latitude, from.geodetic.longitude);
    glm::dvec3 move = to.position - from.position;
    move -= up * glm::dot(move, up);
    const double length = glm::length(move);
    if (length < 1e-9) {
        return to;
    }
    const glm::dvec3 direction = move / length;
    Geodetic feet = from.geodetic;
    feet.height -= body.eyeHeight;
    const Clearance first = clearanceAlong(meshes, feet, direction, length, body);
    if (!first.blocked) {
        return to;
    }
    feet = movedAlong(feet, direction, first.metres);
    // The rest of the move along the wall: its component off the wall's normal.
    const glm::dvec3 rest = direction * (length - first.metres);
    const glm::dvec3 slide = rest - first.normal * glm::dot(rest, first.normal);
    const double slideLength = glm::length(slide);
    if (slideLength > 1e-9) {
        const glm::dvec3 along = slide / slideLength;
        const Clearance second = clearanceAlong(meshes, feet, along, slideLength, body);
        feet = movedAlong(feet, along, second.metres);
    }
    feet.height = from.geodetic.height;
    return CameraNavigation::movedTo(to, feet);
}

}  // namespace sylva
