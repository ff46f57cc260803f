// AmbientOcclusion: the per-primitive ambient term of seed 001 §6.5. A Monte Carlo
// path tracer in a white environment (radiance 1, diffuse bounces with the primitive's
// albedo, `bounces` deep): for each primitive, `samples` random surface points with one
// cosine-distributed direction each (more points, fewer directions: §6.5.2); points
// inside another primitive visible at the same LoD are discarded. LoD awareness: the
// error is a fourth coordinate, a primitive only occludes when its error interval
// contains the sampling primitive's error (§6.5.2). Calibration (§6.5.3): per ellipsoid
// level, rays from outside the plant gather the ambient term at their first hit on the
// level and on the source mesh; the level's ellipsoid terms are scaled so the averages
// agree. Line terms are not calibrated (they span many levels; their traced value is
// kept).
//
// Lines are traced as capsules of their mean radius. Deterministic for a seed, whatever
// the thread count.
#pragma once

#include <cstdint>

#include "sylva/core/base/WorkerPool.h"
#include "sylva/core/plantlod/PlantLod.h"
#include "sylva/core/plantlod/PlantLodProgress.h"
#include "sylva/core/plantlod/PlantModel.h"

namespace sylva {

struct AmbientOcclusionOptions {
    int samples = 64;
    int bounces = 1;  // foliage albedo ~0.15: a second bounce adds about 2 %
    int calibrationRays = 2048;
    std::uint32_t seed = 1;
    WorkerPool* pool = nullptr;  // rays and primitives run on it; null: WorkerPool::shared()
};

// Sets ambientOcclusion of every ellipsoid and line of `lod` (in [0, 1]).
void computeAmbientOcclusion(const PlantModel& model, PlantLod& lod,
                             const AmbientOcclusionOptions& options);

// Mean ambient term over first hits of rays from outside the source mesh (the
// calibration target), exposed for tests.
double sourceMeshAmbientOcclusion(const PlantModel& model, const AmbientOcclusionOptions& options);

}  // namespace sylva
