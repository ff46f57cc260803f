#include "BuildingExtruder.h"

#include "sylva/core/sources/objects/HipRoof.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "sylva/core/geo/Ellipsoid.h"

namespace sylva {

LocalPlane::LocalPlane(double latitude, double longitude)
    : latitude_(latitude),
      longitude_(longitude),
      eastMetres_(Ellipsoid::primeVerticalRadius(latitude) * std::cos(latitude)),
      northMetres_(Ellipsoid::meridionalRadius(latitude)) {}

glm::dvec2 LocalPlane::toLocal(const glm::dvec2& longitudeLatitude) const {
    return {(longitudeLatitude.x - longitude_) * eastMetres_,
            (longitudeLatitude.y - latitude_) * northMetres_};
}

glm::dvec2 LocalPlane::toLongitudeLatitude(const glm::dvec2& local) const {
    return {longitude_ + local.x / eastMetres_, latitude_ + local.y / northMetres_};
}

// Emits flat-shaded convex polygons (3 or 4 corners, counter-clockwise from outside)
// given as (east, north, height above the ellipsoid).
struct BuildingExtruder::Writer {
    const LocalPlane& plane;
    glm::dvec3 origin;
    MeshGeometry& out;

    glm::dvec3 ecef(const glm::dvec3& local) const {
        const glm::dvec2 lonLat = plane.toLongitudeLatitude({local.x, local.y});
        return Ellipsoid::toEcef(Geodetic{lonLat.y, lonLat.x, local.z}) - origin;
    }
    void polygon(std::initializer_list<glm::dvec3> corners, std::uint32_t color) {
        polygon(std::vector<glm::dvec3>(corners), color);
    }
    void polygon(const std::vector<glm::dvec3>& corners, std::uint32_t color) {
        std::vector<glm::dvec3> points;
        for (const glm::dvec3& corner : corners) {
            points.push_back(ecef(corner));
        }
        glm::dvec3 normal(0.0);
        for (std::size_t i = 1; i + 1 < points.size(); ++i) {
            normal += glm::cross(points[i] - points[0], points[i + 1] - points[0]);
        }
        const double length = glm::length(normal);
        if (!(length > 1e-12)) {
            return;  // degenerate (e.g. a zero-height wall)
        }
        normal /= length;
        const auto first = static_cast<std::uint32_t>(out.vertices.size());
        for (const glm::dvec3& p : points) {
            out.vertices.push_back(
                MeshVertex{glm::vec3(p), glm::vec3(normal), color, glm::vec2(0.0f)});
        }
        for (std::uint32_t i = 1; i + 1 < points.size(); ++i) {
            out.indices.insert(out.indices.end(), {first, first + i, first + i + 1});
        }
    }
};

namespace {

bool convex(const Ring& ring) {
    const std::size_t n = ring.size();
    for (std::size_t i = 0; i < n; ++i) {
        const glm::dvec2 a = ring[i], b = ring[(i + 1) % n], c = ring[(i + 2) % n];
        if ((b.x - a.x) * (c.y - b.y) - (b.y - a.y) * (c.x - b.x) < -1e-9) {
            return false;
        }
    }
    return true;
}

// Area centroid of a simple ring (shoelace).
glm::dvec2 centroid(const Ring& ring) {
    double area = 0.0;
    glm::dvec2 sum(0.0);
    for (std::size_t i = 0; i < ring.size(); ++i) {
        const glm::dvec2 a = ring[i], b = ring[(i + 1) % ring.size()];
        const double cross = a.x * b.y - b.x * a.y;
        area += cross;
        sum += (a + b) * cross;
    }
    return std::abs(area) > 1e-12 ? sum / (3.0 * area) : ring.front();
}

double distanceToLine(const glm::dvec2& p, const glm::dvec2& a, const glm::dvec2& b) {
    const glm::dvec2 d = b - a;
    const double length = glm::length(d);
    return length > 0 ? std::abs(d.x * (p.y - a.y) - d.y * (p.x - a.x)) / length
                      : glm::length(p - a);
}

glm::dvec3 at(const glm::dvec2& p, double height) {
    return {p.x, p.y, height};
}

}  // namespace

RoofKind BuildingExtruder::effectiveRoof(const BuildingShape& shape) {
    if (shape.roof == RoofKind::Flat || shape.pitch <= 0.0 || shape.rings.size() != 1) {
        return RoofKind::Flat;
    }
    const Ring& outer = shape.rings.front();
    if ((shape.roof == RoofKind::Gable || shape.roof == RoofKind::Hip) && outer.size() == 4 &&
        convex(outer)) {
        return shape.roof;
    }
    if (shape.roof == RoofKind::Hip && convex(outer)) {
        return RoofKind::Hip;  // any convex footprint: the straight skeleton's roof (HipRoof)
    }
    return convex(outer) ? RoofKind::Pyramid : RoofKind::Flat;
}

Status BuildingExtruder::appendFlatRoof(const BuildingShape& shape, Writer& writer) {
    Result<std::vector<glm::dvec2>> triangles = triangulator_.triangulate(shape.rings);
    if (!triangles) {
        return triangles.error();
    }
    const std::vector<glm::dvec2>& corners = triangles.value();
    for (std::size_t i = 0; i + 2 < corners.size(); i += 3) {
        writer.polygon({at(corners[i], shape.eaves), at(corners[i + 1], shape.eaves),
                        at(corners[i + 2], shape.eaves)},
                       shape.roofColor);
    }
    return Status::success();
}

Status BuildingExtruder::append(const BuildingShape& shape, const LocalPlane& plane,
                                const glm::dvec3& origin, MeshGeometry& out) {
    Writer writer{plane, origin, out};
    // Walls of every ring; holes are clockwise, so their outward side faces the courtyard.
    for (const Ring& ring : shape.rings) {
        for (std::size_t i = 0; i < ring.size(); ++i) {
            const glm::dvec2 a = ring[i], b = ring[(i + 1) % ring.size()];
            writer.polygon(
                {at(a, shape.bottom), at(b, shape.bottom), at(b, shape.eaves), at(a, shape.eaves)},
                shape.wallColor);
        }
    }
    const RoofKind roof = effectiveRoof(shape);
    if (roof == RoofKind::Flat) {
        return appendFlatRoof(shape, writer);
    }
    const Ring& p = shape.rings.front();
    const double rise = std::tan(shape.pitch);
    if (roof == RoofKind::Hip && p.size() != 4) {
        for (const HipRoofFace& face : hipRoof(p, shape.eaves, shape.pitch)) {
            writer.polygon(face.corners, shape.roofColor);
        }
        return Status::success();
    }
    if (roof == RoofKind::Pyramid) {
        const glm::dvec2 apex = centroid(p);
        double reach = std::numeric_limits<double>::infinity();
        for (std::size_t i = 0; i < p.size(); ++i) {
            reach = std::min(reach, distanceToLine(apex, p[i], p[(i + 1) % p.size()]));
        }
        const glm::dvec3 top = at(apex, shape.eaves + rise * reach);
        for (std::size_t i = 0; i < p.size(); ++i) {
            writer.polygon({at(p[i], shape.eaves), at(p[(i + 1) % p.size()], shape.eaves), top},
                           shape.roofColor);
        }
        return Status::success();
    }
    // Gable or hip on four corners: the eaves run along the longer pair of opposite sides.
    const auto length = [&](std::size_t i) { return glm::length(p[(i + 1) % 4] - p[i]); };
    const std::size_t s = length(0) + length(2) >= length(1) + length(3) ? 0 : 1;
    const glm::dvec2 c0 = p[s], c1 = p[(s + 1) % 4], c2 = p[(s + 2) % 4], c3 = p[(s + 3) % 4];
    glm::dvec2 ridge1 = 0.5 * (c1 + c2), ridge2 = 0.5 * (c3 + c0);
    const double halfWidth = 0.25 * (glm::length(c2 - c1) + glm::length(c0 - c3));
    const double ridgeHeight = shape.eaves + rise * halfWidth;
    if (roof == RoofKind::Hip) {
        const double ridgeLength = glm::length(ridge2 - ridge1);
        const glm::dvec2 along = (ridge2 - ridge1) / std::max(ridgeLength, 1e-9);
        const double inset = std::min(halfWidth, 0.5 * ridgeLength);
        ridge1 += along * inset;
        ridge2 -= along * inset;
    }
    const glm::dvec3 r1 = at(ridge1, ridgeHeight), r2 = at(ridge2, ridgeHeight);
    const double e = shape.eaves;
    writer.polygon({at(c0, e), at(c1, e), r1, r2}, shape.roofColor);
    writer.polygon({at(c2, e), at(c3, e), r2, r1}, shape.roofColor);
    const std::uint32_t endColor = roof == RoofKind::Hip ? shape.roofColor : shape.wallColor;
    writer.polygon({at(c1, e), at(c2, e), r1}, endColor);
    writer.polygon({at(c3, e), at(c0, e), r2}, endColor);
    return Status::success();
}

}  // namespace sylva
