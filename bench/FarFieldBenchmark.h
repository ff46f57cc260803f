// FarFieldBenchmark: the far-field canopy's part of `sylva bench vegetation` (issue 21):
// the demo's synthetic Earth (noise relief, woods between 1,700 m and 2,200 m from a mask,
// one generated oak species) seen from the demo's ground camera at five headings, at the
// benchmark's resolution. Per frame, the canopy's G-buffer pass (canopy to the horizon,
// SceneRenderer's farFieldPassSeconds) and the terrain's (terrainPassSeconds), both timed
// to glFinish, after one untimed warm-up frame per heading (tiles, plant model build).
// Metrics: farfield_ms_median, farfield_terrain_ms_median, farfield_vs_terrain (target
// ≤ 0.25), farfield_levels (ring levels the canopy drew in the last frame) and
// farfield_fade_start_m / farfield_fade_end_m (the hand-over band).
//
// Needs a current GL 4.5 context. The project is written to a temporary folder; the oak
// is built once and cached like every plant_model (PlantModelSource::cacheDirectory).
#pragma once

#include <map>
#include <string>

#include "sylva/core/base/Result.h"
#include "sylva/render/gl/ShaderLibrary.h"

namespace sylva::bench {

Result<std::map<std::string, double>> runFarFieldBenchmark(const render::ShaderLibrary& library,
                                                           int width, int height);

}  // namespace sylva::bench
