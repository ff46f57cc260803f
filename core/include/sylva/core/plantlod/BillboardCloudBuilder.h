// BillboardCloudBuilder: billboard clouds (Décoret et al. 2003, "Billboard Clouds for
// Extreme Model Simplification") with the tree extensions of Fuhrmann, Umlauf & Mantler
// 2005 (seed 003 §3.3; seed 000 ch. 4): foliage and branches simplified apart, plane
// search in a discretised dual (Hough) space with angle-weighted face contributions
// (§3.3.1) and a penalty on horizontal planes (§3.3.5), refinement of the best cell,
// a fail-safe plane pick (§3.3.2), post-plane tweaking (§3.3.3), vertex welding
// (§3.3.4), cardboard cross planes for stems (§3.3.6), and per level a texture atlas
// with binary alpha from supersampled software rasterization (§3.3.7). Coarser levels
// are built from the finer level's welded geometry (§3.3.8).
//
// Frame: the PlantModel's (metres, +Z up). The comparison method of issue 6; the
// integrator stores BillboardCloud in .plod files.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "sylva/core/base/Result.h"
#include "sylva/core/plantlod/PlantModel.h"

namespace sylva {

struct BillboardQuad {
    glm::vec3 corners[4];    // counter-clockwise seen from +normal, metres
    glm::vec2 atlasUvs[4];   // texture coordinates in the level's atlas (rows from the top)
    glm::vec3 normal{0.0f};  // unit plane normal
    PlantPart part = PlantPart::Leaf;
    bool cardboard = false;  // a cross plane added for a stem (simplifies no face itself)
};

struct BillboardLevel {
    float epsilon = 0.0f;  // metres: the distance bound of this level
    std::vector<BillboardQuad> quads;
    // Per source triangle (meshes in order, then triangles): the quad it was simplified
    // onto, −1 for degenerate triangles.
    std::vector<int> trianglePlane;
    PlantTexture atlas;  // RGBA8, sRGB colour, binary alpha (0 or 255)
    // Multi-scale RMSE of the level against the source mesh, the metric of the ellipsoid
    // levels (PlantLodLevel::imageError); 0 until measured (addBillboardClouds).
    float imageError = 0.0f;
    // GPU bytes: 4 vertices × (position f32[3] + atlas uv f32[2]) per quad + RGBA8 atlas.
    std::uint64_t byteSize() const {
        return static_cast<std::uint64_t>(quads.size()) * 4u * 20u +
               static_cast<std::uint64_t>(atlas.width) * atlas.height * 4u;
    }
};

// The most billboard-cloud levels a plant may carry: the vegetation renderer's run keys
// have room for this many per species (LodSelector). The builder refuses options asking
// for more, and reading a .plod with more fails naming the file.
inline constexpr std::size_t kMaxBillboardLevels = 16;

struct BillboardCloud {
    std::vector<BillboardLevel> levels;  // finest first, at most kMaxBillboardLevels
};

struct BillboardCloudOptions {
    // Distance bounds per level as fractions of the bounding-sphere radius; a level whose
    // plane count would leave [minimumPlanes, maximumPlanes] (or not drop below the finer
    // level) has its epsilon adjusted.
    std::vector<float> epsilons{0.08f, 0.16f, 0.32f};
    int minimumPlanes = 3;
    int maximumPlanes = 30;
    float horizontalPenalty = 0.6f;                         // §3.3.5: 60 %
    float horizontalCutoff = 50.0f * 3.14159265f / 180.0f;  // radians
    float cardboardCoverage = 0.6f;                         // §3.3.6: accept above this
    float alphaThreshold = 0.3f;                            // §3.3.7: binary alpha cut
    int texelsAcrossModel = 256;  // atlas resolution: texels per bounding diameter
};

class BillboardCloudBuilder {
public:
    // Fails when the model has no triangles or the options are out of range (among them
    // more than kMaxBillboardLevels epsilons).
    static Result<BillboardCloud> build(const PlantModel& model,
                                        const BillboardCloudOptions& options = {});
    // One level as a renderable PlantModel: one mesh of textured quads (two triangles
    // each) per part, one alpha-masked material with the atlas.
    static PlantModel levelModel(const BillboardLevel& level, const std::string& name);
};

}  // namespace sylva
