#include "sylva/core/sources/plants/CanopyProfile.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sylva {

Result<CanopySpecies> CanopyProfile::species(const PlantLod& lod) {
    const glm::dvec3 extent = glm::dvec3(lod.boundsMaximum) - glm::dvec3(lod.boundsMinimum);
    if (!(lod.boundsMaximum.z > 0.0f) || !(extent.x > 0.0) || !(extent.y > 0.0)) {
        return Error{"plant model '" + lod.name + "' has no extent for the far-field canopy"};
    }
    if (lod.ellipsoids.empty()) {
        return Error{"plant model '" + lod.name + "' has no ellipsoids for the far-field canopy"};
    }
    // The coarsest level is what the renderer draws last before the trees leave; the
    // ellipsoids are stored coarse to fine, so they are the leading ones of that level.
    std::uint32_t coarsest = 0;
    for (const LodEllipsoid& e : lod.ellipsoids) {
        coarsest = std::max(coarsest, e.level);
    }
    CanopySpecies out;
    out.height = lod.boundsMaximum.z;
    out.crownWidth = 0.5 * (extent.x + extent.y);
    out.sphereRadius = 0.5 * glm::length(extent);
    double weight = 0.0, occlusion = 0.0;
    glm::dvec3 albedo(0.0);
    for (const LodEllipsoid& e : lod.ellipsoids) {
        if (e.level != coarsest) {
            continue;
        }
        const double w = std::max(double(e.weight), 1e-9);
        albedo += w * glm::dvec3(e.color);
        occlusion += w * e.ambientOcclusion;
        weight += w;
    }
    out.albedo = albedo / weight;
    out.ambientOcclusion = occlusion / weight;
    out.crown = CrownSilhouette::coarsestLevel(lod);
    out.leafLuminance = CrownSilhouette::leafLuminance(lod);
    return out;
}

Result<CanopyProfile> CanopyProfile::make(const PlantsParameters& parameters,
                                          const std::vector<CanopySpecies>& species) {
    if (parameters.species.empty()) {
        return Error{"the far-field canopy needs scattered species (species = {...})"};
    }
    if (species.size() != parameters.species.size()) {
        return Error{"the far-field canopy got " + std::to_string(species.size()) +
                     " species models for " + std::to_string(parameters.species.size()) +
                     " species"};
    }
    double total = 0.0;
    for (const auto& [name, share] : parameters.species) {
        if (!(share > 0.0)) {
            return Error{"species '" + name + "' has no positive share"};
        }
        total += share;
    }
    const double meanScale = 0.5 * (parameters.scaleMinimum + parameters.scaleMaximum);
    CanopyProfile profile;
    profile.smallestSphereRadius_ = std::numeric_limits<double>::infinity();
    profile.ambientOcclusion_ = 0.0;
    for (std::size_t i = 0; i < species.size(); ++i) {
        const double share = parameters.species[i].second / total;
        profile.height_ += share * species[i].height * meanScale;
        profile.crownWidth_ += share * species[i].crownWidth * meanScale;
        profile.albedo_ += share * species[i].albedo;
        profile.ambientOcclusion_ += share * species[i].ambientOcclusion;
        profile.smallestSphereRadius_ = std::min(profile.smallestSphereRadius_,
                                                 species[i].sphereRadius * parameters.scaleMinimum);
    }
    profile.stemsPerSquareMetre_ = parameters.perHectare / 1.0e4;
    profile.species_ = species;
    for (const auto& entry : parameters.species) {
        profile.shares_.push_back(entry.second / total);
    }
    // Scales are drawn uniformly in [a, b]: E[s²] = (a² + ab + b²) / 3.
    const double a = parameters.scaleMinimum, b = parameters.scaleMaximum;
    profile.meanSquareScale_ = (a * a + a * b + b * b) / 3.0;
    return profile;
}

double CanopyProfile::cover(double density) const {
    const double n = std::clamp(density, 0.0, 1.0) * stemsPerSquareMetre_;
    return 1.0 - std::exp(-n * crownWidth_ * kSightDepth);
}

}  // namespace sylva

namespace sylva {

CanopyCrowns CanopyProfile::crowns(const std::vector<LeafState>& states) const {
    CanopyCrowns out;
    glm::dvec3 color(0.0);
    double weight = 0.0;
    for (std::size_t i = 0; i < species_.size(); ++i) {
        const LeafState state = i < states.size() ? states[i] : LeafState{};
        out.species.push_back(
            CrownSilhouette::of(species_[i].crown, state, species_[i].leafLuminance));
        const CrownSilhouette& crown = out.species.back();
        out.topOpaqueArea += shares_[i] * meanSquareScale_ * crown.topOpaqueArea();
        out.sideOpaqueArea += shares_[i] * meanSquareScale_ * crown.sideOpaqueArea();
        out.sideOpaqueFraction += shares_[i] * crown.sideOpaqueFraction();
        color += shares_[i] * crown.sideOpaqueArea() * crown.albedo();
        weight += shares_[i] * crown.sideOpaqueArea();
    }
    out.albedo = weight > 0.0 ? color / weight : albedo_;
    return out;
}

}  // namespace sylva
