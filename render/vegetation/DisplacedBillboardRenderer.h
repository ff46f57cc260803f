// DisplacedBillboardRenderer: the `dmbbc` vegetation method (seed 000 ch. 5), drawing the
// billboard-cloud levels LodSelector picks (the Billboard runs, with the same screen-door
// fades between levels) as ray-marched boxes instead of flat textured quads. Per species
// and level, built at first use (DisplacedBillboardBuilder, CPU): the boxes in a storage
// buffer, the level's atlas (sRGB, mipmapped) and its thick-shell heights (RG16F).
//
// Owned by VegetationRenderer; needs its GL context current for every call.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "sylva/core/base/Result.h"
#include "sylva/core/plantlod/PlantAsset.h"
#include "sylva/core/vegetation/LodSelector.h"
#include "sylva/render/gl/GlHandle.h"
#include "sylva/render/gl/ShaderLibrary.h"
#include "sylva/render/gl/ShaderProgram.h"

namespace sylva::render {

struct DisplacedBillboardFrame {
    glm::mat4 projection{1.0f};  // view → clip (reversed-Z, possibly off-axis)
    float near = 0.1f;           // metres
    glm::vec2 viewport{1.0f};    // pixels
    float band = 0.35f;          // screen-door fade width, ln(error)
};

class DisplacedBillboardRenderer {
public:
    static Result<std::unique_ptr<DisplacedBillboardRenderer>> create(const ShaderLibrary& library);

    // Steps of the ray march at most (one per atlas texel crossed).
    static constexpr int kMaximumSteps = 96;

    // Draws the Billboard runs of `selection` (whose instances are bound as `instances`,
    // DrawInstance per vertex binding 0 of the renderer's vertex array). A level whose
    // displacement cannot be built draws nothing; the first time, the reason is written to
    // stderr naming the plant. Returns the instances drawn.
    std::size_t draw(const LodSelection& selection, const std::vector<SpeciesLod>& lods,
                     const std::vector<std::shared_ptr<const PlantAsset>>& assets,
                     std::uint32_t instances, const DisplacedBillboardFrame& frame);

private:
    struct Level {
        bool built = false, failed = false;
        GlBuffer boxes;
        GlTexture atlas, heights;
        std::uint32_t boxCount = 0;
    };
    DisplacedBillboardRenderer() = default;
    Level& prepare(std::uint32_t species, std::uint32_t level, const PlantAsset& asset);

    ShaderProgram program_;
    GlVertexArray vertexArray_;
    std::vector<std::vector<Level>> levels_;  // per species, per billboard level
};

}  // namespace sylva::render
