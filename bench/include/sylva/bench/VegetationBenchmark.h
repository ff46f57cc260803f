// VegetationBenchmark: `sylva bench vegetation`, seed 001 §3.6 reproduced: trees in forest
// groups on a terrain, a scripted path (overview → descent → inside the forest → turn)
// at 1280×720, rendered with each method — ellipsoid/line LoD, billboard clouds, the full
// source mesh. Per method: the plants' time per frame (frame time minus the same frame
// without plants), the multi-scale RMSE (seed 001 §3.5) against the mesh rendered at 4×
// the resolution and box-filtered down, and the temporal noise (the same metric between
// a frame and the next one, 1/25 s later on the path), as in Figs. 3.15–3.17. Scaling:
// the LoD method with 100,000 and 1,000,000 instances, and the selection alone.
//
// Needs a current GL 4.5 context. The plant (generated oak, LoD and billboard clouds) is
// built at the start, which takes a while and is not timed.
#pragma once

#include <map>
#include <string>

#include "sylva/core/base/Result.h"
#include "sylva/render/gl/ShaderLibrary.h"

namespace sylva::bench {

struct VegetationBenchmarkOptions {
    int width = 1280;
    int height = 720;
    int trees = 10000;
    int leaves = 1000;         // of the generated oak
    int framesPerSegment = 4;  // four segments
    int referenceScale = 4;    // supersampling of the mesh reference
    bool scaling = true;       // also 100k and 1M instances
    std::string framesFolder;  // if set, every frame of each method is written there
    // The methods to run (profiling); without the mesh there is no reference image and
    // no RMSE, without the LoD no scaling runs.
    bool lod = true, billboards = true, mesh = true;
    // Occlusion culling of the plants on the path (VegetationSettings::occlusionCulling);
    // `culled_fraction_inside_forest` is measured with it on either way.
    bool occlusion = true;
    bool points = true;     // point clouds with approximate visible sets (seed 000 ch. 3)
    bool dmbbc = true;      // displacement-mapped billboard clouds (seed 000 ch. 5)
    bool impostors = true;  // the impostors method (issue 21)
    bool farField = true;   // the far-field canopy's pass against the terrain's (FarFieldBenchmark)
};

struct VegetationBenchmarkResult {
    std::map<std::string, double> metrics;
    std::string json() const;  // {"suite":"vegetation","metrics":{...}}
};

Result<VegetationBenchmarkResult> runVegetationBenchmark(const render::ShaderLibrary& library,
                                                         const VegetationBenchmarkOptions& options);

}  // namespace sylva::bench
