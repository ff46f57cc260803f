// ShadowThresholds: per level of a plant's ellipsoid/line LoD, the noise alpha thresholds
// with which the level casts as much sun shadow as the source plant's leaves (issue 16: a
// crown's shadow density must not depend on the level the shadow pass picks).
//
// Why thresholds of their own: each level's threshold and scale are calibrated by image
// error (seed 001 §3.4.1, EllipsoidHierarchy) over the builder's views, three quarters of
// them 10° above the horizon. Seen from there the perforated cluster ellipsoids cover
// about as much as the leaves; seen from higher up they cover less, because leaves lie
// mostly flat and a cluster's noise holes do not: the golden test oak's coarse levels
// cover 0.080–0.091 of the 55° views where its leaves cover 0.112, so their shadows let
// 20–30 % more sun through than the leaves'. The shadow pass (shaders/shadows/
// ellipsoid_shadow.vert) draws each level with a threshold interpolated between the one
// matching the leaves' coverage 10° above the horizon (`low`) and 55° above (`high`) by
// the sun's elevation in the plant's frame (10° and below: low; 55° and above: high).
//
// Coverage: the share of pixels of PrimitiveRasterizer's orthographic views at that
// elevation (8 views: six at 10°, two at 55°; the plant's bounding sphere) where a leaf
// is hit — the source: its leaf meshes, alpha-tested; a level: its ellipsoids (front hit,
// then the back hit where the front is perforated, as the renderer draws them).
// Ellipsoids stand for the leaves; lines (the branches, calibrated on their own) are left
// as they are. A level's coverage does not increase with its threshold (raising it only
// removes noise cells), so each threshold is found by bisection (12 steps) in
// [0, kMaximumShadowThreshold]; when even an unperforated level covers less than the
// leaves, it is 0.
//
// Frames: model space of the PlantModel/PlantLod (metres). Thresholds in [0, 1).
// Failure: none; a model without leaf meshes (nothing to compare with) keeps the levels'
// own thresholds. Cost: about 2 × 14 renders of each level at resolution² (CPU, levels
// and elevations on the shared WorkerPool; docs/benchmarks.md gives the time).
// Thread safety: a pure function of its arguments.
#pragma once

#include <vector>

#include "sylva/core/plantlod/PlantLod.h"
#include "sylva/core/plantlod/PlantModel.h"

namespace sylva {

inline constexpr float kMaximumShadowThreshold = 0.97f;
inline constexpr float kShadowLowElevationDegrees = 10.0f;
inline constexpr float kShadowHighElevationDegrees = 55.0f;

struct ShadowThreshold {
    float low = 0.0f;   // for a sun 10° (or less) above the plant's horizon
    float high = 0.0f;  // for a sun 55° (or more) above it
};

// One entry per lod.levels entry (finest first).
std::vector<ShadowThreshold> shadowThresholds(const PlantModel& model, const PlantLod& lod,
                                              int resolution = 128);

// For tests and measurements: the share of the views at `high` (55°) or not (10°) that
// the source model's leaves cover, and that the ellipsoids of level `level` of `lod`
// cover drawn at `threshold` (< 0: their own).
double sourceShadowCoverage(const PlantModel& model, const PlantLod& lod, bool high,
                            int resolution = 128);
double levelShadowCoverage(const PlantLod& lod, std::size_t level, float threshold, bool high,
                           int resolution = 128);

}  // namespace sylva
