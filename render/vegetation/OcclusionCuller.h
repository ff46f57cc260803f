// OcclusionCuller: the render side of the vegetation's occlusion culling (issue 21 item 2).
// It splits a frame's plants into rings of distance drawn nearest first and, before each
// ring, reads the bound framebuffer's depth (terrain, meshes and the nearer rings drawn
// so far) back into a DepthPyramid (sylva_core) that LodSelector culls the ring against.
//
// On llvmpipe the depth buffer is CPU memory, so the read-back costs a copy (a few ms at
// 1280×720) and a pipeline drain; on a GPU a read-back stalls, and a pyramid built on
// the GPU (or the previous frame's) would be the better choice — see docs/benchmarks.md.
//
// Needs the GL context current and the target framebuffer bound for reading.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "sylva/core/vegetation/DepthPyramid.h"
#include "sylva/render/vegetation/VegetationRenderer.h"

namespace sylva::render {

// One ring: instances with centres in (minimumDistance, maximumDistance] (metres; 0 as
// the maximum: unbounded), culled against `pyramid` (null: not culled).
struct OcclusionRing {
    double minimumDistance = 0.0;
    double maximumDistance = 0.0;
    const DepthPyramid* pyramid = nullptr;
};

class OcclusionCuller {
public:
    // The ring limits of `settings` (one unbounded ring when culling is off): ends at
    // occluderDistance × occlusionRingRatio^k, the last ring open; `maximumDistance`
    // (metres, 0 = none) ends the list early. Rings no batch's bounding sphere reaches
    // (from `eye`, ECEF metres) are left out — each ring costs a read-back — but the last
    // ring always stays.
    static std::vector<OcclusionRing> rings(const VegetationSettings& settings,
                                            const std::vector<const InstanceBatch*>& batches,
                                            const glm::dvec3& eye);

    // Reads the depth of the framebuffer bound for reading (pixelsWide × pixelsHigh,
    // reversed-Z floats) and rebuilds the pyramid for `projection` and `near`. The
    // returned pyramid lives until the next update().
    const DepthPyramid& update(int pixelsWide, int pixelsHigh, const glm::dmat4& projection,
                               double near);

private:
    std::vector<float> depth_;  // kept between frames
    DepthPyramid pyramid_;
};

}  // namespace sylva::render
