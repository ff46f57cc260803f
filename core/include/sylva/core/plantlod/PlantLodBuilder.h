// PlantLodBuilder: PlantModel → PlantLod, the whole of seed 001 ch. 3 plus the
// sequential arrays and ambient occlusion of §6.2 and §6.5:
//   1. reference images of the source mesh (leaves, branches, both) from every view;
//   2. leaf ellipsoids and the ellipsoid cluster levels (EllipsoidHierarchy);
//   3. the line width calibration and the line merge hierarchy (LineHierarchy);
//   4. error intervals in metres per pixel (§6.3): an ellipsoid level is used while its
//      mean ellipsoid diameter spans at least 5 pixels; a line is replaced by its merged
//      parent once the parent is thinner than one pixel (widths taken as the maximum
//      over the merge subtree, so intervals nest like a sequential point tree);
//   5. the multi-scale RMSE of each level (ellipsoids + the lines drawn at its error)
//      against the full source mesh;
//   6. ambient occlusion per primitive (AmbientOcclusion).
//
// The hook for importers: anything that yields a PlantModel can be built; the CLI's
// `--synthetic N` uses makeSyntheticPlant until the importer is wired in.
//
// Deterministic for a seed, whatever `threads` is. Fails (Error naming the plant) when
// the model has neither leaves nor a skeleton or has non-finite coordinates.
#pragma once

#include <cstdint>

#include "sylva/core/base/Result.h"
#include "sylva/core/plantlod/BillboardCloudBuilder.h"
#include "sylva/core/plantlod/LineHierarchy.h"
#include "sylva/core/plantlod/PlantLod.h"
#include "sylva/core/plantlod/PlantLodProgress.h"
#include "sylva/core/plantlod/PlantModel.h"

namespace sylva {

struct PlantLodOptions {
    int threads = 0;  // ≤ 0: all cores
    std::uint32_t seed = 1;
    int restarts = 4;      // EM restarts per level (seed 001: four suffice)
    int resolution = 128;  // error images, pixels per side (a power of two)
    int views = 8;
    int supersampling = 2;
    int ambientOcclusionSamples = 64;  // per primitive; 0 disables (AO = 1)
    float ellipsoidPixels = 5.0f;      // mean ellipsoid diameter at the level switch
    float linePixels = 1.0f;           // line width at the merge switch
    LineHierarchyOptions lines;
};

Result<PlantLod> buildPlantLod(const PlantModel& model, const PlantLodOptions& options,
                               const PlantLodProgressCallback& progress = {});

// Multi-scale RMSE of what a renderer draws at tolerated error `error` (metres per
// pixel) against the full source mesh, over the builder's standard views.
double plantLodImageError(const PlantModel& model, const PlantLod& lod, float error,
                          const PlantLodOptions& options);

// Builds the billboard clouds of `model` (BillboardCloudBuilder, seed 003) into
// lod.billboards and measures each level's multi-scale RMSE against the source mesh with
// the views and resolution of `options`, the metric of the ellipsoid levels. Fails like
// BillboardCloudBuilder::build (the message names the plant); lod is unchanged then.
Status addBillboardClouds(const PlantModel& model, PlantLod& lod, const PlantLodOptions& options,
                          const BillboardCloudOptions& billboardOptions = {});

// Multi-scale RMSE of `candidate` (any mesh, e.g. a billboard level's model) against the
// full source model, over the builder's standard views.
double plantMeshImageError(const PlantModel& source, const PlantModel& candidate,
                           const PlantLodOptions& options);

}  // namespace sylva
