// SceneRenderer: renders one view of one scenario into an image: clipmap update,
// terrain into the G-buffer, shading, read-back. The CLI, the tests and later the
// viewer and `sylva watch` all render through it.
//
// Needs a current GL 4.5 context for create() and render(); destroy it while that
// context is current. Data errors (a tile that cannot be produced) come back as
// Result errors naming the source and tile; nothing is written anywhere.
#pragma once

#include <cstdint>
#include <future>
#include <map>
#include <memory>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "sylva/core/base/Result.h"
#include "sylva/core/scene/Camera.h"
#include "sylva/core/seasons/PlantDate.h"
#include "sylva/core/sources/graph/SourceGraph.h"
#include "sylva/core/sources/plants/PlantModelSource.h"
#include "sylva/core/vegetation/VegetationStream.h"
#include "sylva/render/gl/Framebuffer.h"
#include "sylva/render/objects/MeshRenderer.h"
#include "sylva/render/scene/SampleAccumulator.h"
#include "sylva/render/shading/AmbientOcclusionPass.h"
#include "sylva/render/shading/ShadingPass.h"
#include "sylva/render/shadows/ShadowMaps.h"
#include "sylva/render/terrain/TerrainRenderer.h"
#include "sylva/render/vegetation/FarFieldCanopy.h"
#include "sylva/render/vegetation/VegetationRenderer.h"

namespace sylva::render {

struct RenderSettings {
    int width = 1280;
    int height = 720;
    // Pixel rows the terrain's clipmap levels are chosen for (0: `height`). The viewer
    // draws budget-reduced frames with the window's levels, so a still view refined to
    // full resolution wants the same tiles (no wanted list swinging between the two).
    int levelRows = 0;
    glm::dvec3 sunDirection{1, 0, 0};  // ECEF unit vector towards the sun
    bool atmosphere = true;
    bool ocean = true;
    AtmosphereParameters atmosphereParameters;  // render { visibility, haze_height }
    // Exposure: luminance x exposureScale(EV100) x `exposure`. EV100 is `ev100` when set
    // (a physical camera), else metered (incident light) at the ground point under the
    // camera from the sun and sky of the atmosphere model; from space (above the
    // atmosphere) for the sun at the zenith. One viewpoint, sun and atmosphere always
    // give one EV100, whatever the scenario shows.
    std::optional<double> ev100;
    double exposure = 1.0;
    // Batch rendering waits until every wanted terrain level's tiles are ready (the
    // image is then independent of thread timing); interactive use draws what is
    // ready and lets the provider's workers catch up (seed 001 §4.7).
    bool waitForTiles = true;
    // Also read back the linear radiance (Image::radiance), e.g. for EXR output.
    bool linearOutput = false;
    // Anti-aliasing: samples per pixel (1..SampleAccumulator::kMaxSamples), each a full
    // render with a sub-pixel shifted projection, averaged in linear light (SampleAccumulator).
    int samples = 1;
    VegetationSettings vegetation;
    // The date plants are shown at (issue 21 item 3): their season (leaf-on, leaf-off,
    // autumn; Phenology) and their growth since planting (GrowthCurve). None: full grown,
    // full leaf. Batch rendering sets it from render `date`, else the view's time.
    std::optional<PlantDate> plantDate;
    // The far-field canopy beyond vegetation.maximumDistance (FarFieldCanopy); off while
    // that distance is 0 (the C++ default) or band is 0.
    FarFieldSettings farField;
    MeshSettings meshes;  // buildings and models of the scenario's `meshes` layers
    // Sun shadows (cascaded shadow maps, seed 001 §7.1): the terrain always casts; more
    // casters (not owned; e.g. the mesh/building renderer of issue 17, test objects) are
    // drawn into every cascade but the terrain-only one after the SceneRenderer's own.
    ShadowSettings shadows;
    std::vector<ShadowCaster*> shadowCasters;
    // Test output: the sun visibility of the shadow maps instead of light
    // (ShadingSettings::sunVisibilityOutput).
    bool sunVisibilityOutput = false;
    // Screen-space ambient occlusion of the sky light (seed 001 §7.1; AmbientOcclusionPass).
    AmbientOcclusionSettings ambientOcclusion;
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
    double groundHeight = 0;           // metres: the ground under the camera used
    double ev100 = 0;                  // the camera exposure used (set or metered)
    double gpuSeconds = 0;             // draw + shade (every sample) + read-back
    double terrainPassSeconds = 0;     // the terrain's G-buffer passes alone (to glFinish)
    double vegetationPassSeconds = 0;  // selection, upload and the plants' G-buffer passes
    double meshPassSeconds = 0;        // buildings and models: streaming and G-buffer pass
    MeshStatistics meshes;
    double shadowPassSeconds = 0;            // all cascades of the shadow maps (to glFinish)
    double ambientOcclusionPassSeconds = 0;  // SSAO and its blur, every sample (to glFinish)
    VegetationStatistics vegetation;
    VegetationStreamStatistics vegetationStream;
    double farFieldPassSeconds = 0;  // the far-field canopy's G-buffer passes (to glFinish)
    FarFieldFrame farField;          // its hand-over distances and levels
    // Interactive frames (waitForTiles false) never wait; what they did not have yet:
    std::size_t pendingSpecies = 0;  // plant assets still being built (their plants not drawn)
    int groundLevel = -1;            // ring level the nadir height came from (-1: last frame's)
    // Anything wanted still arriving: terrain or canopy levels, instance tiles, plant
    // assets, the nadir height of the finest level. False for batch frames.
    bool pending = false;
};

class SceneRenderer {
public:
    static Result<std::unique_ptr<SceneRenderer>> create(const ShaderLibrary& library,
                                                         const TerrainSettings& settings);
    ~SceneRenderer();

    // Fails if the camera is below the terrain, a tile fails or settings.samples is outside
    // 1..SampleAccumulator::kMaxSamples.
    Result<Image> render(const TerrainLayers& layers, TileProvider& provider, const Camera& camera,
                         const RenderSettings& settings);

    // Reversed-Z perspective with an infinite far plane (depth = near / distance),
    // off-axis by `lensShift` (fractions of the image width and height, Camera::lensShift).
    static glm::dmat4 projection(double verticalFov, double aspect, double near,
                                 const glm::dvec2& lensShift = glm::dvec2(0.0));

    const RenderStatistics& statistics() const { return statistics_; }
    // Waits for the plant assets being built in the background (interactive frames start
    // them); call before the source graphs they belong to are dropped.
    void finishAssetBuilds();
    // Builds (on this thread) and uploads the plant species of `layers` that are not yet
    // drawn, as a frame waiting for tiles would; fails with the first species' error.
    Status prepareSpecies(const TerrainLayers& layers);
    // Reversed-Z depth of the last render (0 = nothing drawn), rows top to bottom; and
    // the near plane distance (metres) it was rendered with: distance = near / depth.
    std::vector<float> depth() const { return gbuffer_.readDepth(); }
    double near() const { return near_; }
    TerrainRenderer& terrain() { return *terrain_; }
    VegetationRenderer& vegetation() { return *vegetation_; }
    FarFieldCanopy& farField() { return *farField_; }
    MeshRenderer& meshes() { return *meshes_; }
    // The shadow maps of the last render (no cascades when shadows were off).
    const ShadowMaps& shadowMaps() const { return *shadowMaps_; }

private:
    SceneRenderer() = default;
    Status ensureTargets(int width, int height, bool linearOutput);
    // Ground height, visible levels and the clipmap update (seed 001 Alg. 3); the levels
    // that are ready to draw.
    Result<LevelRange> prepareTerrain(const TerrainLayers& layers, TileProvider& provider,
                                      const Camera& camera, const RenderSettings& settings);
    // Interactive frames: the ground under the camera from the finest ring level whose tile
    // is ready (the finer ones requested), else the last frame's; only the very first
    // frame waits, for the coarsest level. Sets statistics_.groundLevel.
    Result<double> readyGround(const TerrainLayers& layers, TileProvider& provider,
                               const Camera& camera, const RenderSettings& settings);
    // The plants to draw: settings.instanceBatches and the streamed plants layers.
    Result<std::vector<const InstanceBatch*>> streamVegetation(const TerrainLayers& layers,
                                                               TileProvider& provider,
                                                               const Camera& camera,
                                                               const RenderSettings& settings);
    // One sample: terrain, buildings/models and plants into the G-buffer with `projection`, shaded
    // into output_.
    // With `renderShadows`, draws the sun's shadow maps (after the plants, whose selection
    // the vegetation caster reuses) before shading. Fails if a shadow caster fails.
    Status drawSample(const Camera& camera, const glm::dmat4& projection, const LevelRange& levels,
                      const std::vector<const InstanceBatch*>& batches,
                      const RenderSettings& settings, bool renderShadows);
    // The cascades of settings.shadows with the terrain, the plants just drawn, the
    // scenario's meshes and settings.shadowCasters.
    Status drawShadowMaps(const Camera& camera, const std::vector<const InstanceBatch*>& batches,
                          const RenderSettings& settings);
    // The far-field canopy of the frame: its sources, hand-over and clipmaps (once per
    // image); the draw (once per sample) returns the trees' settings with its fade.
    Status prepareFarField(const TerrainLayers& layers, TileProvider& provider,
                           const Camera& camera, const LevelRange& levels,
                           const RenderSettings& settings);
    VegetationSettings drawFarField(const Camera& camera, const glm::dmat4& projection,
                                    const RenderSettings& settings);
    // EV100 of an incident-light meter at the ground under the camera (see RenderSettings).
    double meterEv100(const Camera& camera, double groundHeight, const RenderSettings& settings);
    // The stream layers of the scenario's plants sources; registers each species'
    // asset with the vegetation renderer on first use (building it may take seconds).
    // With `wait` false (interactive) an asset is built on a background thread and its
    // species is left out (statistics_.pendingSpecies) until it is ready.
    Result<std::vector<VegetationStreamLayer>> vegetationLayers(const TerrainLayers& layers,
                                                                bool wait);
    // The species index of `model`'s asset: registered now (wait), or once its background
    // build finished; nothing while it is still building.
    Result<std::optional<std::uint32_t>> speciesFor(const PlantModelSource& model, bool wait);
    // Makes the scenario's buildings and models near the camera resident (once per image).
    Status streamMeshes(const TerrainLayers& layers, TileProvider& provider, const Camera& camera,
                        const RenderSettings& settings);
    // Draws the resident buildings and models into the G-buffer (once per sample).
    void drawMeshes(const Camera& camera, const glm::dmat4& projection,
                    const RenderSettings& settings);

    std::unique_ptr<TerrainRenderer> terrain_;
    std::unique_ptr<VegetationRenderer> vegetation_;
    std::unique_ptr<FarFieldCanopy> farField_;
    std::unique_ptr<MeshRenderer> meshes_;
    bool meshesStreamed_ = false;  // this image's scenario has mesh layers
    double groundHeight_ = 0;      // metres: the ground under the camera (prepareTerrain)
    bool groundKnown_ = false;     // groundHeight_ was set by an earlier frame
    VegetationStream vegetationStream_;
    std::map<std::uint64_t, std::uint32_t> speciesOfModel_;  // model content hash -> species
    std::unique_ptr<AmbientOcclusionPass> ambientOcclusion_;
    // Plant assets being built in the background, by model content hash.
    std::map<std::uint64_t, std::future<Result<std::shared_ptr<const PlantAsset>>>> assetBuilds_;
    std::unique_ptr<ShadingPass> shading_;
    std::unique_ptr<SampleAccumulator> accumulator_;
    std::unique_ptr<ShadowMaps> shadowMaps_;
    Framebuffer gbuffer_;
    Framebuffer output_;
    RenderStatistics statistics_;
    double near_ = 1.0;
};

}  // namespace sylva::render
