// PointCloudBuilder: point-sampled plants (seed 000 ch. 3, "Fast approximate visible sets
// for point-cloud vegetation"): the source mesh's surface sampled area-uniformly, every
// sample a small oriented disc (a surfel) with the surface normal, the linear colour of
// the material × texture at that point and a radius from the area it stands for. Leaf
// samples are alpha-tested against the texture like the mesh (seed 001 §3.2), so the
// cloud has the holes of the leaves' cut-outs.
//
// Samples per triangle: its share of the count (the fraction by chance), spread by a
// randomly offset R2 low-discrepancy sequence so that the discs close the surface.
//
// Frame: the PlantModel's (metres, +Z up). Built at load by the vegetation renderer (no
// disk cache: 40,000 samples and their visible sets take ~0.1–0.3 s per species), so there
// is no file format to version; the builder is deterministic for (model, options).
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "sylva/core/base/Result.h"
#include "sylva/core/plantlod/PlantModel.h"

namespace sylva {

// One sample: a disc of `radius` at `position` facing `normal` (unit; leaves are
// two-sided, the renderer flips it towards the viewer). 32 bytes, std430-friendly.
struct PlantPoint {
    glm::vec3 position{0.0f};  // model frame, metres
    float radius = 0.0f;       // metres
    glm::vec3 normal{0.0f, 0.0f, 1.0f};
    std::uint32_t color = 0;  // sRGB-encoded RGB (R in the low byte), 8 bits each, alpha 255
};

struct PointCloudOptions {
    int samples = 40000;  // samples drawn before the alpha test (the kept count is lower)
    // Disc area = coverage × (surface area per sample): > 1 so that the discs overlap and
    // close the surface (evenly spread samples need about 1.2).
    float coverage = 2.5f;
    std::uint32_t seed = 1;
};

struct PointCloud {
    std::vector<PlantPoint> points;
    glm::vec3 boundsMinimum{0.0f}, boundsMaximum{0.0f};  // of the positions, model frame
};

class PointCloudBuilder {
public:
    // Fails when the model has no triangle of positive area or the options are out of range
    // (samples < 1 or > 10,000,000, coverage <= 0).
    static Result<PointCloud> build(const PlantModel& model, const PointCloudOptions& options = {});

    // Linear RGB to and from PlantPoint::color (sRGB codes, so darks keep their precision).
    static std::uint32_t packColor(glm::vec3 linear);
    static glm::vec3 unpackColor(std::uint32_t packed);
};

}  // namespace sylva
