// The sun shadows' part of `sylva bench shading`: every frame of the terrain benchmark's
// flight (bench/TerrainFlight.h) and of the vegetation benchmark's forest path
// (bench/BenchForest.h) is rendered with and without shadows (tiles and plants warmed up
// first, both waiting for every tile, so the two renders draw the same), and the median
// frame times (SceneRenderer's draw + shadow maps + shade + read-back, without the clipmap
// update) are compared. Keys: `shadow_frame_ratio` (the larger of the two scenes' ratios
// of medians, with / without), `shadow_frame_ratio_terrain`, `shadow_frame_ratio_forest`,
// `shadow_ms_median_terrain`, `shadow_ms_median_forest` (the shadow maps alone); both
// without screen-space ambient occlusion. The same frames are rendered a third time with
// shadows and SSAO (AmbientOcclusionPass): `ssao_frame_ratio` (the larger of the scenes'
// ratios of medians, shadows + SSAO / shadows), `ssao_frame_ratio_terrain`,
// `ssao_frame_ratio_forest`, `ssao_ms_median_terrain`, `ssao_ms_median_forest` (the pass
// and its blur alone).
//
// Those renders repeat each camera after its warm-up, so the shadow cache always hits
// (a still camera). The moving camera: stretches of `movingFrames` consecutive cameras a
// small step apart (the flight continued level at 1 km, 3 m per frame, and at 50 m,
// 0.5 m per frame; the forest path walked in from its edge at 10 cm per frame and the
// turn inside at 1° per frame), warmed up once along the stretch, then timed in order with
// and without shadows with no warm-up at a frame's own camera: `shadow_frame_ratio_moving`
// (the larger of the scenes' ratios of medians), `shadow_frame_ratio_moving_terrain`,
// `_forest`, `shadow_frame_ratio_moving_mean` (ratios of means, which see the frames that
// redraw a cascade), `shadow_ms_median_moving_*`, `shadow_ms_max_moving_*`,
// `shadow_redrawn_cascades_moving_*` (the fraction of cascades drawn rather than copied).
#pragma once

#include <map>
#include <string>

#include "sylva/bench/ShadingBenchmark.h"
#include "sylva/core/base/Result.h"
#include "sylva/render/gl/ShaderLibrary.h"

namespace sylva::bench {

Status measureShadows(const render::ShaderLibrary& library, const ShadingBenchmarkOptions& options,
                      std::map<std::string, double>& metrics);

}  // namespace sylva::bench
