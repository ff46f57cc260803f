#include "sylva/core/sources/plants/CrownSilhouette.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace sylva {

namespace {

constexpr glm::dvec3 kLuminance{0.2126, 0.7152, 0.0722};

// One ellipsoid prepared for projections: the inverse of its shape matrix (unit sphere
// → model), its opacity and seasonal colour.
struct Prepared {
    glm::dvec3 center{0.0};
    glm::dmat3 shape{1.0};  // columns: axis × radius
    glm::dmat3 inverse{1.0};
    double opacity = 0.0;
    glm::dvec3 color{0.0};
};

struct Projection {
    double opaque = 0.0, outline = 0.0;
    glm::dvec3 colorSum{0.0};  // Σ opacity × colour × area
    double colorWeight = 0.0;
};

// The orthographic projection of `crown` along `direction` (unit) on a resolution² grid.
Projection project(const std::vector<Prepared>& crown, const glm::dvec3& direction,
                   int resolution) {
    const glm::dvec3 u = glm::normalize(std::abs(direction.z) < 0.9
                                            ? glm::cross(direction, glm::dvec3(0.0, 0.0, 1.0))
                                            : glm::cross(direction, glm::dvec3(1.0, 0.0, 0.0)));
    const glm::dvec3 v = glm::cross(direction, u);
    glm::dvec2 low(std::numeric_limits<double>::infinity());
    glm::dvec2 high(-std::numeric_limits<double>::infinity());
    for (const Prepared& e : crown) {
        // Half-extent of the ellipsoid along a unit axis a: sqrt(aᵀ M Mᵀ a).
        const glm::dmat3 s = e.shape * glm::transpose(e.shape);
        const glm::dvec2 half(std::sqrt(glm::dot(u, s * u)), std::sqrt(glm::dot(v, s * v)));
        const glm::dvec2 middle(glm::dot(e.center, u), glm::dot(e.center, v));
        low = glm::min(low, middle - half);
        high = glm::max(high, middle + half);
    }
    Projection out;
    if (crown.empty() || !(high.x > low.x) || !(high.y > low.y)) {
        return out;
    }
    const glm::dvec2 step = (high - low) / double(resolution);
    const double cellArea = step.x * step.y;
    for (int j = 0; j < resolution; ++j) {
        for (int i = 0; i < resolution; ++i) {
            const glm::dvec2 p = low + (glm::dvec2(i, j) + 0.5) * step;
            const glm::dvec3 point = p.x * u + p.y * v;
            double transmission = 1.0;
            bool inside = false;
            glm::dvec3 color(0.0);
            double weight = 0.0;
            for (const Prepared& e : crown) {
                // The line point + s·direction meets the ellipsoid where |y + s e| <= 1.
                const glm::dvec3 y = e.inverse * (point - e.center);
                const glm::dvec3 d = e.inverse * direction;
                const double along = glm::dot(y, d) / glm::dot(d, d);
                if (glm::dot(y, y) - along * along * glm::dot(d, d) > 1.0) {
                    continue;
                }
                inside = true;
                transmission *= 1.0 - e.opacity;
                color += e.opacity * e.color;
                weight += e.opacity;
            }
            out.opaque += (1.0 - transmission) * cellArea;
            out.outline += inside ? cellArea : 0.0;
            if (weight > 0.0) {
                // The cell's opaque area in the mean colour of what stops its rays.
                out.colorSum += (1.0 - transmission) * cellArea * color / weight;
                out.colorWeight += (1.0 - transmission) * cellArea;
            }
        }
    }
    return out;
}

}  // namespace

double CrownSilhouette::ellipsoidOpacity(double threshold, double leafFraction) {
    if (!(leafFraction > 0.0)) {
        return 0.0;
    }
    const double t = std::max(threshold, 0.0);
    return std::clamp(leafFraction * (1.0 - t * t), 0.0, 1.0);
}

std::vector<LodEllipsoid> CrownSilhouette::coarsestLevel(const PlantLod& lod) {
    std::uint32_t coarsest = 0;
    for (const LodEllipsoid& e : lod.ellipsoids) {
        coarsest = std::max(coarsest, e.level);
    }
    std::vector<LodEllipsoid> out;
    for (const LodEllipsoid& e : lod.ellipsoids) {
        if (e.level == coarsest) {
            out.push_back(e);
        }
    }
    return out;
}

double CrownSilhouette::leafLuminance(const PlantLod& lod) {
    double sum = 0.0, weight = 0.0;
    for (const LodEllipsoid& e : lod.ellipsoids) {
        if (e.level == 0) {
            sum += double(e.weight) * glm::dot(glm::dvec3(e.color), kLuminance);
            weight += e.weight;
        }
    }
    return weight > 0.0 ? sum / weight : 0.1;
}

CrownSilhouette CrownSilhouette::of(const std::vector<LodEllipsoid>& ellipsoids,
                                    const LeafState& state, double leafLuminance, int resolution) {
    resolution = std::max(resolution, 4);
    // Autumn as vegetation.glsl's seasonalLeafColour: towards the autumn colour scaled by
    // the leaf's luminance over the species' mean.
    const glm::dvec3 autumn = glm::dvec3(state.autumnColour) / std::max(leafLuminance, 1e-4);
    std::vector<Prepared> crown;
    for (const LodEllipsoid& e : ellipsoids) {
        Prepared p;
        p.opacity = ellipsoidOpacity(e.alphaThreshold, state.leafFraction);
        const glm::dmat3 shape(glm::dvec3(e.axes[0]) * double(e.radii.x),
                               glm::dvec3(e.axes[1]) * double(e.radii.y),
                               glm::dvec3(e.axes[2]) * double(e.radii.z));
        if (!(p.opacity > 0.0) || !(std::abs(glm::determinant(shape)) > 1e-12)) {
            continue;
        }
        p.center = glm::dvec3(e.center);
        p.shape = shape;
        p.inverse = glm::inverse(shape);
        const glm::dvec3 color(e.color);
        p.color = glm::mix(color, autumn * glm::dot(color, kLuminance), double(state.autumn));
        crown.push_back(p);
    }
    CrownSilhouette out;
    const Projection top = project(crown, {0.0, 0.0, -1.0}, resolution);
    out.topOpaque_ = top.opaque;
    out.topOutline_ = top.outline;
    Projection side;
    for (int k = 0; k < 4; ++k) {
        const double azimuth = k * std::numbers::pi / 4.0;
        const Projection one =
            project(crown, {std::cos(azimuth), std::sin(azimuth), 0.0}, resolution);
        side.opaque += one.opaque / 4.0;
        side.outline += one.outline / 4.0;
        side.colorSum += one.colorSum;
        side.colorWeight += one.colorWeight;
    }
    out.sideOpaque_ = side.opaque;
    out.sideOutline_ = side.outline;
    if (side.colorWeight > 0.0) {
        out.albedo_ = side.colorSum / side.colorWeight;
    }
    return out;
}

}  // namespace sylva
