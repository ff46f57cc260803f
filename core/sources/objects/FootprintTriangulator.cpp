#include "FootprintTriangulator.h"

#include <geos_c.h>

#include <memory>

namespace sylva {

namespace {

GEOSContextHandle_t handleOf(void* context) {
    return static_cast<GEOSContextHandle_t>(context);
}

struct GeometryDeleter {
    GEOSContextHandle_t handle;
    void operator()(GEOSGeometry* geometry) const { GEOSGeom_destroy_r(handle, geometry); }
};
using GeometryPointer = std::unique_ptr<GEOSGeometry, GeometryDeleter>;

// A closed GEOS linear ring from an open ring; null on failure.
GEOSGeometry* makeRing(GEOSContextHandle_t handle, const Ring& ring) {
    std::vector<double> buffer;
    buffer.reserve(2 * (ring.size() + 1));
    for (const glm::dvec2& p : ring) {
        buffer.push_back(p.x);
        buffer.push_back(p.y);
    }
    buffer.push_back(ring.front().x);
    buffer.push_back(ring.front().y);
    GEOSCoordSequence* sequence = GEOSCoordSeq_copyFromBuffer_r(
        handle, buffer.data(), static_cast<unsigned>(ring.size() + 1), 0, 0);
    if (sequence == nullptr) {
        return nullptr;
    }
    return GEOSGeom_createLinearRing_r(handle, sequence);  // takes the sequence
}

GeometryPointer makePolygon(GEOSContextHandle_t handle, const std::vector<Ring>& rings) {
    GeometryPointer none(nullptr, GeometryDeleter{handle});
    if (rings.empty() || rings.front().size() < 3) {
        return none;
    }
    std::vector<GEOSGeometry*> parts;
    for (const Ring& ring : rings) {
        GEOSGeometry* geometry = ring.size() >= 3 ? makeRing(handle, ring) : nullptr;
        if (geometry == nullptr) {
            for (GEOSGeometry* made : parts) {
                GEOSGeom_destroy_r(handle, made);
            }
            return none;
        }
        parts.push_back(geometry);
    }
    GEOSGeometry* polygon = GEOSGeom_createPolygon_r(
        handle, parts.front(), parts.size() > 1 ? parts.data() + 1 : nullptr,
        static_cast<unsigned>(parts.size() - 1));  // takes the rings
    return GeometryPointer(polygon, GeometryDeleter{handle});
}

}  // namespace

FootprintTriangulator::FootprintTriangulator() : context_(GEOS_init_r()) {}

FootprintTriangulator::~FootprintTriangulator() {
    GEOS_finish_r(handleOf(context_));
}

std::string FootprintTriangulator::invalidReason(const std::vector<Ring>& rings) {
    GEOSContextHandle_t handle = handleOf(context_);
    GeometryPointer polygon = makePolygon(handle, rings);
    if (!polygon) {
        return "a ring has fewer than three corners";
    }
    if (GEOSisValid_r(handle, polygon.get()) == 1) {
        return {};
    }
    char* reason = GEOSisValidReason_r(handle, polygon.get());
    std::string text = reason != nullptr ? reason : "invalid polygon";
    GEOSFree_r(handle, reason);
    return text;
}

Result<std::vector<glm::dvec2>> FootprintTriangulator::triangulate(const std::vector<Ring>& rings) {
    GEOSContextHandle_t handle = handleOf(context_);
    GeometryPointer polygon = makePolygon(handle, rings);
    if (!polygon) {
        return Error{"a ring has fewer than three corners"};
    }
    GeometryPointer triangles(GEOSConstrainedDelaunayTriangulation_r(handle, polygon.get()),
                              GeometryDeleter{handle});
    if (!triangles) {
        return Error{"GEOS could not triangulate the footprint"};
    }
    std::vector<glm::dvec2> corners;
    const int count = GEOSGetNumGeometries_r(handle, triangles.get());
    for (int i = 0; i < count; ++i) {
        const GEOSGeometry* triangle = GEOSGetGeometryN_r(handle, triangles.get(), i);
        const GEOSGeometry* ring = GEOSGetExteriorRing_r(handle, triangle);
        const GEOSCoordSequence* sequence =
            ring != nullptr ? GEOSGeom_getCoordSeq_r(handle, ring) : nullptr;
        double buffer[8];
        unsigned size = 0;
        if (sequence == nullptr || GEOSCoordSeq_getSize_r(handle, sequence, &size) == 0 ||
            size != 4 || GEOSCoordSeq_copyToBuffer_r(handle, sequence, buffer, 0, 0) == 0) {
            return Error{"GEOS returned a triangulation that is not made of triangles"};
        }
        const glm::dvec2 a(buffer[0], buffer[1]), b(buffer[2], buffer[3]), c(buffer[4], buffer[5]);
        const double twiceArea = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
        corners.push_back(a);
        corners.push_back(twiceArea >= 0 ? b : c);
        corners.push_back(twiceArea >= 0 ? c : b);
    }
    return corners;
}

}  // namespace sylva
