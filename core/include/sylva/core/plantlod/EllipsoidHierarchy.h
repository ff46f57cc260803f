// EllipsoidHierarchy: leaves → ellipsoids → levels of ellipsoid clusters (seed 001
// §3.3.1, §3.3.3, §3.4.1, Algorithm 1).
//
// Import: each leaf (a connected piece of a Leaf mesh; vertices at equal positions are
// welded, so unwelded quads still form one leaf) is sampled area-uniformly, samples
// whose texture alpha fails the material's cutoff (0.5 by default) are discarded, and a
// PCA of the survivors gives the leaf ellipsoid; its weight is the surviving leaf area.
//
// Levels: K = N/4, N/16, … down to one cluster. For each K, `restarts` EM runs (in
// parallel) cluster the leaf centres weighted by area; the fuzzy responsibilities
// weight a PCA of the leaf ellipsoids (the mixture's moment match, so a cluster of one
// leaf is that leaf); ellipsoids under 1 % of the largest surface area are dropped; the
// run with the lowest image error against the rendered source leaves is kept. Then the
// level's noise alpha threshold t and primitive scale are calibrated by image error
// (§3.3.3, §3.4.1), with the per-cluster noise mip level l = 0.5 (1 + log2 Σ_i w_ij).
//
// Deviation from the thesis: EM starts from K distinct random leaf centres instead of
// K random points in the bounding box. A tree crown's bounding box is mostly empty, so
// box-initialised clusters die in EM and a level ends with far fewer than K clusters.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "sylva/core/base/WorkerPool.h"
#include "sylva/core/plantlod/GaussianMixture.h"
#include "sylva/core/plantlod/PlantLod.h"
#include "sylva/core/plantlod/PlantLodProgress.h"
#include "sylva/core/plantlod/PlantModel.h"
#include "sylva/core/plantlod/PrimitiveRasterizer.h"

namespace sylva {

// Leaf ellipsoids with radii = sqrt(eigenvalues) (scale 1), level 0, colour the mean
// sample colour. Deterministic for a seed.
std::vector<LodEllipsoid> importLeafEllipsoids(const PlantModel& model, std::uint32_t seed,
                                               int samplesPerLeaf = 32);

// Fig. 3.7 / 3.8: one ellipsoid per live cluster from the responsibilities. With
// `hardAssignment` every leaf goes wholly to its most probable cluster instead (the
// variant the thesis rejects: it loses small clusters next to large ones). Clusters
// that receive no weight produce no ellipsoid.
std::vector<LodEllipsoid> ellipsoidsFromAssignments(std::span<const LodEllipsoid> leaves,
                                                    const GaussianMixtureFit& fit,
                                                    bool hardAssignment = false);

// Multi-scale RMSE of ellipsoids (drawn with `style`) against per-view reference images,
// averaged over views level by level, the views rendered in parallel on `pool`.
double ellipsoidImageError(const PrimitiveRasterizer& rasterizer,
                           std::span<const LodEllipsoid> ellipsoids,
                           const std::vector<std::vector<float>>& reference,
                           const EllipsoidStyle& style, WorkerPool& pool);

struct EllipsoidHierarchyOptions {
    int restarts = 4;
    WorkerPool* pool = nullptr;  // restarts and views run on it; null: WorkerPool::shared()
    std::uint32_t seed = 1;
    double discardAreaFraction = 0.01;
    GaussianMixtureOptions mixture;
};

struct EllipsoidLevel {
    std::vector<LodEllipsoid> ellipsoids;  // scale baked into radii, threshold set
    int clusterTarget = 0;                 // K of this level (0 for the imported leaves)
    double imageError = 0.0;               // against the source leaves, calibrated
    float primitiveScale = 1.0f;
    float alphaThreshold = 0.0f;
};

// Level 0 = the calibrated leaf ellipsoids, then coarser levels to one cluster.
// `reference`: the source leaves rendered by `rasterizer` (resolved, per view).
std::vector<EllipsoidLevel> buildEllipsoidHierarchy(
    std::span<const LodEllipsoid> leaves, const PrimitiveRasterizer& rasterizer,
    const std::vector<std::vector<float>>& reference, const EllipsoidHierarchyOptions& options,
    const PlantLodProgressCallback& progress, double progressStart, double progressEnd);

}  // namespace sylva
