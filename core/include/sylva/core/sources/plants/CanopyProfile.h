// CanopyProfile: the forest canopy of one plants source seen from afar, the "canopy
// proxy × vegetation cover" of seed 000 ch. 6 (the combined elevation map CEM = DEM +
// proxy × cover), derived from what the near field draws instead of a LIDAR patch:
//  - the proxy height H is the share-weighted mean top height of the species' LoDs
//    (PlantLod bounds, +Z up) times the mean instance scale, so the far-field canopy top
//    is where the drawn trees' tops are on average;
//  - the cover is the line-of-sight opacity of the stand: stems are a Poisson process of
//    n = density × per_hectare / 10⁴ per m², each crown blocks a width w (share-weighted
//    mean crown width × mean scale), so a horizontal ray crossing kSightDepth metres of
//    stand passes with probability exp(−n w kSightDepth) (Beer–Lambert for a Boolean
//    model). A forest seen at a grazing angle from kilometres away is opaque up to about
//    its top height unless it is very sparse; the cover scales the height down only there;
//  - canopy height above the ground = H × cover, in metres.
// The albedo (linear RGB) and ambient occlusion are the leaf-area-weighted means of each
// species' coarsest ellipsoid level; they are stored in the canopy's tiles (full leaf).
// What the drawn trees show at the hand-over on a given date is crowns(): each species'
// CrownSilhouette in its leaf state (opaque areas seen from above and from the side and
// the colour they show), which the far-field shader uses for its gaps and tone, so the
// seasons change the far field without new tiles.
//
// Pure CPU data; make() fails (naming the plants source) when a species' LoD has no
// extent or no ellipsoids, or the source scatters no species (points only).
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "sylva/core/base/Result.h"
#include "sylva/core/plantlod/PlantLod.h"
#include "sylva/core/seasons/Phenology.h"
#include "sylva/core/sources/plants/CrownSilhouette.h"
#include "sylva/core/sources/plants/PlantsSource.h"

namespace sylva {

// One species as the canopy sees it (model frame, metres, unit scale).
struct CanopySpecies {
    double height = 0.0;        // top of the model above its base
    double crownWidth = 0.0;    // mean of the model's east and north extents
    double sphereRadius = 0.0;  // half the bounds' diagonal (the selector's culling sphere)
    glm::dvec3 albedo{0.0};     // linear RGB of the coarsest ellipsoids, leaf-area weighted
    double ambientOcclusion = 1.0;
    std::vector<LodEllipsoid> crown;  // the coarsest level's ellipsoids (CrownSilhouette)
    double leafLuminance = 0.1;       // CrownSilhouette::leafLuminance (autumn colour)
};

// The stand's crowns in one set of leaf states (CanopyProfile::crowns).
struct CanopyCrowns {
    std::vector<CrownSilhouette> species;  // unit scale, indexed like the profile's species
    // Share-weighted opaque projected areas of one instance at the scatter's scales (mean
    // of scale²), m²: from above and from the side (CrownSilhouette).
    double topOpaqueArea = 0.0;
    double sideOpaqueArea = 0.0;
    // Share-weighted opaque share of a crown's side outline, [0, 1].
    double sideOpaqueFraction = 0.0;
    // Share- and side-opaque-area-weighted colour the crowns show (linear RGB); the full-
    // leaf profile albedo when nothing is opaque (leaf-off: the shader shows no canopy).
    glm::dvec3 albedo{0.0};
};

class CanopyProfile {
public:
    // Depth of stand a far-away line of sight is taken to cross (metres).
    static constexpr double kSightDepth = 100.0;

    // The canopy description of one LoD; fails when the LoD has no extent or no ellipsoids.
    static Result<CanopySpecies> species(const PlantLod& lod);

    // From the source's parameters and its species (indexed like the `species` entries of
    // the parameters; shares are normalised here). Fails when the counts differ, a share
    // is not positive or no species is scattered.
    static Result<CanopyProfile> make(const PlantsParameters& parameters,
                                      const std::vector<CanopySpecies>& species);

    // Line-of-sight opacity [0, 1] where the density mask is `density` (clamped to [0, 1]).
    double cover(double density) const;
    // Canopy height above the ground (metres) where the density mask is `density`.
    double canopyHeight(double density) const { return height_ * cover(density); }

    // The crowns in the species' leaf states (indexed like the species given to make();
    // missing entries are full leaf). Costs a few projections of the coarsest level per
    // species: evaluate once per date, not per frame.
    CanopyCrowns crowns(const std::vector<LeafState>& states) const;

    double height() const { return height_; }                            // H, metres
    double crownWidth() const { return crownWidth_; }                    // w, metres
    double stemsPerSquareMetre() const { return stemsPerSquareMetre_; }  // at density 1
    // Smallest instance culling radius (smallest species sphere × scale minimum): the
    // trees that leave the selector first through `minimumPixels`.
    double smallestSphereRadius() const { return smallestSphereRadius_; }
    const glm::dvec3& albedo() const { return albedo_; }
    double ambientOcclusion() const { return ambientOcclusion_; }

private:
    double height_ = 0.0;
    double crownWidth_ = 0.0;
    double stemsPerSquareMetre_ = 0.0;
    double smallestSphereRadius_ = 0.0;
    glm::dvec3 albedo_{0.0};
    double ambientOcclusion_ = 1.0;
    std::vector<CanopySpecies> species_;
    std::vector<double> shares_;    // normalised
    double meanSquareScale_ = 1.0;  // E[scale²] of a uniform scale
};

}  // namespace sylva
