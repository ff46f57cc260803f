#include "sylva/core/sources/objects/HipRoof.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "sylva/core/base/Check.h"

namespace sylva {

namespace {

struct SideLine {
    glm::dvec2 inward;  // unit normal pointing into the polygon (left of a CCW side)
    double offset;      // d(p) = dot(inward, p) - offset
};

// Keeps the part of a convex polygon where dot(normal, p) <= limit.
std::vector<glm::dvec2> clip(const std::vector<glm::dvec2>& polygon, const glm::dvec2& normal,
                             double limit) {
    std::vector<glm::dvec2> out;
    const std::size_t n = polygon.size();
    for (std::size_t i = 0; i < n; ++i) {
        const glm::dvec2 a = polygon[i], b = polygon[(i + 1) % n];
        const double da = glm::dot(normal, a) - limit, db = glm::dot(normal, b) - limit;
        if (da <= 0.0) {
            out.push_back(a);
        }
        if ((da < 0.0 && db > 0.0) || (da > 0.0 && db < 0.0)) {
            out.push_back(a + (b - a) * (da / (da - db)));
        }
    }
    return out;
}

double signedArea(const std::vector<glm::dvec2>& polygon) {
    double area = 0.0;
    for (std::size_t i = 0; i < polygon.size(); ++i) {
        const glm::dvec2 a = polygon[i], b = polygon[(i + 1) % polygon.size()];
        area += a.x * b.y - b.x * a.y;
    }
    return 0.5 * area;
}

}  // namespace

std::vector<HipRoofFace> hipRoof(const std::vector<glm::dvec2>& ring, double eaves, double pitch) {
    const std::size_t n = ring.size();
    SYLVA_CHECK(n >= 3);
    std::vector<SideLine> lines;
    for (std::size_t i = 0; i < n; ++i) {
        const glm::dvec2 d = ring[(i + 1) % n] - ring[i];
        const double length = glm::length(d);
        SYLVA_CHECK(length > 0.0);
        const glm::dvec2 inward(-d.y / length, d.x / length);
        lines.push_back({inward, glm::dot(inward, ring[i])});
        SYLVA_CHECK(glm::dot(inward, ring[(i + 2) % n]) - lines.back().offset >= -1e-6);
    }
    // A tolerance for sides on one line (consecutive collinear corners): the first side
    // keeps their common face.
    const double scale = std::max(1.0, std::sqrt(std::abs(signedArea(ring))));
    const double rise = std::tan(pitch);
    std::vector<HipRoofFace> faces;
    for (std::size_t i = 0; i < n; ++i) {
        std::vector<glm::dvec2> face(ring.begin(), ring.end());
        for (std::size_t j = 0; j < n && face.size() >= 3; ++j) {
            if (j == i) {
                continue;
            }
            // d_i(p) <= d_j(p)  ⇔  dot(inward_i - inward_j, p) <= offset_i - offset_j.
            const glm::dvec2 normal = lines[i].inward - lines[j].inward;
            double limit = lines[i].offset - lines[j].offset;
            if (glm::length(normal) < 1e-12) {
                if (j > i) {
                    continue;  // the same line, later side: this face keeps the region
                }
                limit -= 1e-9 * scale;  // the same line, earlier side: it has the region
            }
            face = clip(face, normal, limit);
        }
        // Several sides meeting in one skeleton node leave repeated corners there.
        std::vector<glm::dvec2> corners;
        for (const glm::dvec2& p : face) {
            if (corners.empty() || glm::length(p - corners.back()) > 1e-9 * scale) {
                corners.push_back(p);
            }
        }
        while (corners.size() > 1 &&
               glm::length(corners.front() - corners.back()) <= 1e-9 * scale) {
            corners.pop_back();
        }
        face = std::move(corners);
        if (face.size() < 3 || signedArea(face) <= 1e-12 * scale * scale) {
            continue;
        }
        HipRoofFace out;
        out.side = i;
        for (const glm::dvec2& p : face) {
            const double d = std::max(0.0, glm::dot(lines[i].inward, p) - lines[i].offset);
            out.corners.emplace_back(p.x, p.y, eaves + rise * d);
        }
        faces.push_back(std::move(out));
    }
    return faces;
}

}  // namespace sylva
