// SceneRenderer: renders one view of one scenario into an image: clipmap update,
// terrain into the G-buffer, shading, read-back. The CLI, the tests and later the
// viewer and `sylva watch` all render through it.
//
// Needs a current GL 4.5 context for create() and render(); destroy it while that
// context is current. Data errors (a tile that cannot be produced) come back as
// Result errors naming the source and tile; nothing is written anywhere.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "sylva/core/base/Result.h"
#include "sylva/core/scene/Camera.h"
#include "sylva/core/sources/graph/SourceGraph.h"
#include "sylva/core/vegetation/VegetationStream.h"
#include "sylva/render/gl/Framebuffer.h"
#include "sylva/render/shading/ShadingPass.h"
#include "sylva/render/terrain/TerrainRenderer.h"
#include "sylva/render/vegetation/VegetationRenderer.h"

namespace sylva::render {

struct RenderSettings {
    int width = 1280;
    int height = 720;
    glm::dvec3 sunDirection{1, 0, 0};  // ECEF unit vector towards the sun
    bool atmosphere = true;
    bool ocean = true;
    double exposure = 1.0;
    // Batch rendering waits until every wanted terrain level's tiles are ready (the
    // image is then independent of thread timing); interactive use draws what is
    // ready and lets the provider's workers catch up (seed 001 §4.7).
    bool waitForTiles = true;
    // Also read back the linear radiance (Image::radiance), e.g. for EXR output.
    bool linearOutput = false;
    VegetationSettings vegetation;
    // Plants handed in directly (tests, benchmarks), drawn with the species of
    // vegetation(); the `plants` layers of the scenario are streamed besides.
    std::vector<const InstanceBatch*> instanceBatches;
};

struct Image {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> pixels;  // RGBA8, sRGB, rows top to bottom
    // With RenderSettings::linearOutput: RGBA floats, linear radiance × exposure (before
    // tone mapping), alpha 1, rows top to bottom; `pixels` = sRGB(1 − exp(−radiance)).
    std::vector<float> radiance;
};

struct RenderStatistics {
    TerrainFrameStatistics terrain;
    double heightAboveTerrain = 0;     // metres
    double gpuSeconds = 0;             // draw + shade + read-back
    double terrainPassSeconds = 0;     // the terrain's G-buffer pass alone (to glFinish)
    double vegetationPassSeconds = 0;  // selection, upload and the plants' G-buffer pass
    VegetationStatistics vegetation;
    VegetationStreamStatistics vegetationStream;
};

class SceneRenderer {
public:
    static Result<std::unique_ptr<SceneRenderer>> create(const ShaderLibrary& library,
                                                         const TerrainSettings& settings);
    ~SceneRenderer();

    // Fails if the camera is below the terrain or a tile fails.
    Result<Image> render(const TerrainLayers& layers, TileProvider& provider, const Camera& camera,
                         const RenderSettings& settings);

    // Reversed-Z perspective with an infinite far plane (depth = near / distance),
    // off-axis by `lensShift` (fractions of the image width and height, Camera::lensShift).
    static glm::dmat4 projection(double verticalFov, double aspect, double near,
                                 const glm::dvec2& lensShift = glm::dvec2(0.0));

    const RenderStatistics& statistics() const { return statistics_; }
    // Reversed-Z depth of the last render (0 = nothing drawn), rows top to bottom; and
    // the near plane distance (metres) it was rendered with: distance = near / depth.
    std::vector<float> depth() const { return gbuffer_.readDepth(); }
    double near() const { return near_; }
    TerrainRenderer& terrain() { return *terrain_; }
    VegetationRenderer& vegetation() { return *vegetation_; }

private:
    SceneRenderer() = default;
    Status ensureTargets(int width, int height, bool linearOutput);
    // The stream layers of the scenario's plants sources; registers each species'
    // asset with the vegetation renderer on first use (building it may take seconds).
    Result<std::vector<VegetationStreamLayer>> vegetationLayers(const TerrainLayers& layers);

    std::unique_ptr<TerrainRenderer> terrain_;
    std::unique_ptr<VegetationRenderer> vegetation_;
    VegetationStream vegetationStream_;
    std::map<std::uint64_t, std::uint32_t> speciesOfModel_;  // model content hash -> species
    std::unique_ptr<ShadingPass> shading_;
    Framebuffer gbuffer_;
    Framebuffer output_;
    RenderStatistics statistics_;
    double near_ = 1.0;
};

}  // namespace sylva::render
