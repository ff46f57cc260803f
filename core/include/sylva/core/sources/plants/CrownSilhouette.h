// CrownSilhouette: the projected silhouette of one tree crown as the drawn trees show it
// where they hand over to the far-field canopy (issue 21): the ellipsoids of the LoD's
// coarsest level, each thinned and recoloured by a leaf state exactly as ellipsoid.vert /
// ellipsoid.frag do it, projected orthographically from above and from the side.
//
// Opacity of one ellipsoid. The ray-cast ellipsoid tests its noise (alpha threshold t) at
// the front hit and, where that is perforated, again at the back: a ray through it stops
// with probability 1 − t². With a leaf fraction f the shader raises the threshold to
// sqrt(1 − f (1 − t²)), so the ray stops with f (1 − t²); f = 0 draws nothing. Rays
// through several ellipsoids meet independent noise: transmission multiplies.
//
// The far field needs the opaque projected area A = ∫ (1 − T) dA of a crown (T the
// transmission along the ray through a point of the projection plane): for stems of a
// Poisson process of n per m², a line of sight through a stand passes with
// exp(−n A) (the Boolean model with partly transparent grains), which is what the
// drawn stand shows on average. Top: looking down (−Z); side: the mean over four
// horizontal azimuths (0°, 45°, 90°, 135°). The albedo is the opacity-weighted mean of
// the seasonal colours over the side view (what a far, grazing line of sight sees).
//
// Model frame, metres, before the instance scale (scale the areas by s²). Pure CPU.
// Estimated on a `resolution`² grid over each projection's bounds (relative error of the
// areas about 1/resolution on a smooth outline). An empty crown (no ellipsoids, or leaf
// fraction 0) has zero areas and a black albedo.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "sylva/core/plantlod/PlantLod.h"
#include "sylva/core/seasons/Phenology.h"

namespace sylva {

class CrownSilhouette {
public:
    // The silhouette of `ellipsoids` (usually one level of a PlantLod) in `state`, with
    // `leafLuminance` the species' mean leaf luminance (the autumn colour is scaled per
    // ellipsoid by its luminance over that, as vegetation.glsl's seasonalLeafColour does).
    static CrownSilhouette of(const std::vector<LodEllipsoid>& ellipsoids, const LeafState& state,
                              double leafLuminance, int resolution = 96);

    // The ellipsoids of a LoD's coarsest level (the last drawn before the trees leave).
    static std::vector<LodEllipsoid> coarsestLevel(const PlantLod& lod);
    // Leaf-area-weighted mean luminance of the finest level's leaves (level 0), as the
    // vegetation renderer computes it for the autumn colour; 0.1 without leaves.
    static double leafLuminance(const PlantLod& lod);

    // Opacity an ellipsoid of alpha threshold `threshold` gives a ray at leaf fraction
    // `leafFraction`: min(1, f (1 − t²)), 0 when f <= 0.
    static double ellipsoidOpacity(double threshold, double leafFraction);

    double topOpaqueArea() const { return topOpaque_; }    // m², seen from above
    double sideOpaqueArea() const { return sideOpaque_; }  // m², mean over the azimuths
    double topOutlineArea() const { return topOutline_; }  // m², where any ellipsoid is
    double sideOutlineArea() const { return sideOutline_; }
    // Opaque share of the outline seen from the side, [0, 1] (0 for an empty crown).
    double sideOpaqueFraction() const {
        return sideOutline_ > 0.0 ? sideOpaque_ / sideOutline_ : 0.0;
    }
    const glm::dvec3& albedo() const { return albedo_; }  // linear RGB

private:
    double topOpaque_ = 0.0, sideOpaque_ = 0.0;
    double topOutline_ = 0.0, sideOutline_ = 0.0;
    glm::dvec3 albedo_{0.0};
};

}  // namespace sylva
