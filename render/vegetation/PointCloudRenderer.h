// PointCloudRenderer: the `points` vegetation method (seed 000 ch. 3). Per species, built
// at first use from the source mesh (PointCloudBuilder, VisibleSets; CPU, ~0.1–0.3 s):
// the samples in a storage buffer and the samples of every view-direction cell in one
// index buffer. Per frame, every instance of a LodSelector run (species × error bucket)
// finds the cell of its view direction (model frame); instances are grouped by cell and
// each group is one instanced point draw of a prefix of the cell's set — the samples with
// the largest contributions, as many as the bucket's screen size needs (two per pixel of
// the bounding disc), their discs enlarged so the prefix covers what the whole set does.
//
// Owned by VegetationRenderer; needs its GL context current for every call.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "sylva/core/base/Result.h"
#include "sylva/core/plantlod/PlantAsset.h"
#include "sylva/core/plantlod/VisibleSets.h"
#include "sylva/core/vegetation/LodSelector.h"
#include "sylva/render/gl/GlHandle.h"
#include "sylva/render/gl/ShaderLibrary.h"
#include "sylva/render/gl/ShaderProgram.h"

namespace sylva::render {

struct PointCloudFrame {
    glm::mat4 projection{1.0f};  // view → clip (reversed-Z, possibly off-axis)
    float near = 0.1f;           // metres
    glm::vec2 viewport{1.0f};    // pixels
    float pixelAngle = 1e-3f;    // radians per pixel
    float maximumPointSize = 1.0f;
};

class PointCloudRenderer {
public:
    static Result<std::unique_ptr<PointCloudRenderer>> create(const ShaderLibrary& library);

    // Samples per species (before the alpha test); a prefix may draw fewer.
    static constexpr int kSamples = 40000;
    // Discs are drawn this much larger than sampled: the visible sets miss a few samples
    // (orthographic views from the cell corners), and the sampling is even only within a
    // triangle; 1.2 closes the holes of the analytic sphere (PointCloudRendererTest).
    static constexpr float kSplatScale = 1.2f;
    // Samples drawn per pixel of an instance's bounding disc (the prefix length).
    static constexpr double kSamplesPerPixel = 2.0;

    // Draws the Primitives runs of `selection` as point clouds (species indices as in
    // `assets`). Species whose model has no triangle draw nothing; the first time, the
    // reason is written to stderr naming the plant. Returns the samples drawn.
    std::size_t draw(const LodSelection& selection, const std::vector<SpeciesLod>& lods,
                     const std::vector<std::shared_ptr<const PlantAsset>>& assets,
                     const PointCloudFrame& frame);

    // The number of samples of a prefix for an instance bounded by `sphereRadius` (metres)
    // at tolerated error `error` (metres per pixel), out of `setSize`.
    static std::uint32_t prefixLength(double sphereRadius, double error, std::uint32_t setSize);

private:
    struct Species {
        bool built = false, failed = false;
        std::uint32_t firstSample = 0;  // in the shared sample buffer
        std::uint32_t firstIndex = 0;   // of cell 0 in the shared index buffer
        VisibleSets sets;
    };
    struct Group {
        std::uint32_t species = 0, cell = 0, bucket = 0;
        std::uint32_t firstInstance = 0, instanceCount = 0;
    };
    PointCloudRenderer() = default;
    void prepare(std::uint32_t species, const PlantAsset& asset);
    void groupInstances(const LodSelection& selection, const std::vector<SpeciesLod>& lods);

    ShaderProgram program_;
    std::vector<Species> species_;
    // CPU copies of every species' samples (std430 pairs of vec4) and cell indices; the GPU
    // buffers are re-created when a species is added.
    std::vector<glm::vec4> samples_;
    std::vector<std::uint32_t> indices_;
    GlBuffer sampleBuffer_, indexBuffer_, instanceBuffer_;
    std::size_t instanceCapacity_ = 0;
    GlVertexArray vertexArray_;
    std::vector<DrawInstance> grouped_;
    std::vector<Group> groups_;
};

}  // namespace sylva::render
