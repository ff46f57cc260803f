#include "sylva/core/analysis/ProposalTargets.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "sylva/core/geo/Ellipsoid.h"

namespace sylva {

namespace {

// A turning axis steeper than this (cosine to the model's +Z) is a yaw: it does not raise
// anything, so its part counts as posed.
constexpr double kVerticalAxisCosine = 0.9;

struct Sweep {
    int part = -1;          // the turning part whose rotation a vertex follows; -1: posed
    glm::dmat4 base{1.0};   // model frame of that part before its own rotation
    glm::dvec3 axis{0.0};   // unit, in that part's frame
    glm::dmat4 below{1.0};  // the vertex's part frame → the turning part's frame (posed)
};

glm::dvec3 transformPoint(const glm::dmat4& m, const glm::dvec3& p) {
    return glm::dvec3(m * glm::dvec4(p, 1.0));
}

// The nearest part on the chain from `part` to the root that turns about a non-vertical
// axis, with the transforms a vertex of `part` needs to be swept with it.
Sweep sweepOf(const MeshModel& model, const std::vector<glm::dmat4>& posed,
              const std::vector<float>& angles, int part) {
    Sweep sweep;
    for (int i = part; i >= 0; i = model.parts[std::size_t(i)].parent) {
        const ModelPart& candidate = model.parts[std::size_t(i)];
        const double angle = std::size_t(i) < angles.size() ? double(angles[std::size_t(i)]) : 0.0;
        const glm::dmat4 rotation = glm::rotate(glm::dmat4(1.0), angle, candidate.axis);
        const glm::dmat4 base = posed[std::size_t(i)] * glm::inverse(rotation);
        const glm::dvec3 axisInModel = glm::normalize(glm::dmat3(base) * candidate.axis);
        if (std::abs(axisInModel.z) >= kVerticalAxisCosine)
            continue;
        sweep.part = i;
        sweep.base = base;
        sweep.axis = glm::normalize(candidate.axis);
        sweep.below =
            glm::inverse(rotation) * glm::inverse(posed[std::size_t(i)]) * posed[std::size_t(part)];
        return sweep;
    }
    return sweep;
}

}  // namespace

double highestPointAbove(const MeshModel& model, const ModelPlacement& placement,
                         const glm::dvec3& up) {
    const std::vector<glm::dmat4> posed = model.partTransforms(placement.partAngles);
    // Height of a model-frame vector along `up`: up · (axes · v) = (axesᵀ up) · v.
    const glm::dvec3 heightOf = glm::transpose(placement.axes) * up;
    double highest = -INFINITY;
    for (std::size_t p = 0; p < model.parts.size(); ++p) {
        const Sweep sweep = sweepOf(model, posed, placement.partAngles, int(p));
        // For a swept vertex q (turning part's frame, before its rotation) the model point
        // is base · R(θ) q; R(θ) q runs on the circle of centre a (a·q) and radius
        // |q − a (a·q)| in the plane ⟂ a, so the largest height over θ is
        // g·a (a·q) + r |g − (g·a) a| with g the height gradient in that frame.
        const glm::dvec3 g = glm::transpose(glm::dmat3(sweep.base)) * heightOf;
        const double offset = glm::dot(heightOf, glm::dvec3(sweep.base[3]));
        const double gAlong = glm::dot(g, sweep.axis);
        const double gAcross = glm::length(g - gAlong * sweep.axis);
        for (const MeshVertex& vertex : model.parts[p].geometry.vertices) {
            const glm::dvec3 v(vertex.position);
            double height;
            if (sweep.part < 0) {
                height = glm::dot(heightOf, transformPoint(posed[p], v));
            } else {
                const glm::dvec3 q = transformPoint(sweep.below, v);
                const double along = glm::dot(sweep.axis, q);
                const double radius = glm::length(q - along * sweep.axis);
                height = offset + gAlong * along + radius * gAcross;
            }
            highest = std::max(highest, height);
        }
    }
    return highest;
}

Result<std::vector<ProposalTop>> proposalTops(const std::string& sourceName,
                                              const MeshSource& source, TileProvider& provider) {
    auto bounds = source.bounds();
    if (!bounds)
        return bounds.error();
    const TileKey first = MeshSource::keyOf({bounds->west, bounds->north});
    const TileKey last = MeshSource::keyOf({bounds->east, bounds->south});
    std::vector<ProposalTop> tops;
    for (int y = first.y; y <= last.y; ++y)
        for (int x = first.x; x <= last.x; ++x) {
            auto tile = source.tile(TileKey{MeshSource::kTileLevel, 0, x, y}, provider);
            if (!tile)
                return tile.error();
            const MeshTile& meshes = **tile;
            for (std::size_t i = 0; i < meshes.placements.size(); ++i) {
                const ModelPlacement& placement = meshes.placements[i];
                const Geodetic origin = Ellipsoid::toGeodetic(placement.position);
                const glm::dvec3 up = Ellipsoid::surfaceNormal(origin.latitude, origin.longitude);
                ProposalTop top;
                top.label = sourceName + (placement.featureId >= 0
                                              ? " feature " + std::to_string(placement.featureId)
                                              : " placement " + std::to_string(tops.size() + 1));
                top.latitude = origin.latitude;
                top.longitude = origin.longitude;
                top.height = highestPointAbove(*meshes.model, placement, up);
                if (!(top.height > 0.0))
                    return Error{top.label + ": the model has nothing above its origin"};
                tops.push_back(top);
            }
        }
    if (tops.empty())
        return Error{"'" + sourceName +
                     "' places no model (an objects source of point or line "
                     "features is needed)"};
    return tops;
}

}  // namespace sylva
