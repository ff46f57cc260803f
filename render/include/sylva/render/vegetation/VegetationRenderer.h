// VegetationRenderer: plants on the terrain (seed 001 ch. 6). Per species it keeps the
// sequential primitive arrays of the PlantLod in storage buffers (ellipsoids, lines),
// the source mesh and the billboard-cloud levels as instanced triangle meshes; per frame
// LodSelector picks each instance's level and draw() issues a few instanced draws per
// species and level bucket into the G-buffer (albedo + ambient occlusion, view normal,
// reversed-Z depth), after the terrain so that hidden plants fail the depth test.
//
// Instances come either as InstanceBatches handed in (tests, benchmarks) or streamed
// from `plants` sources by VegetationStream (SceneRenderer does that).
//
// Needs a current GL 4.5 context for create(), addSpecies() and draw(); destroy it while
// that context is current. Errors (a shader that does not compile) come back as Result.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "sylva/core/base/Result.h"
#include "sylva/core/plantlod/BillboardCloudBuilder.h"
#include "sylva/core/plantlod/PlantAsset.h"
#include "sylva/core/scene/Camera.h"
#include "sylva/core/seasons/Phenology.h"
#include "sylva/core/vegetation/LodSelector.h"
#include "sylva/render/gl/GlHandle.h"
#include "sylva/render/gl/ShaderLibrary.h"
#include "sylva/render/gl/ShaderProgram.h"
#include "sylva/render/shadows/ShadowCaster.h"
#include "sylva/render/vegetation/FarFieldFade.h"
#include "sylva/render/vegetation/ImpostorRenderer.h"

namespace sylva::render {

struct VegetationMesh;  // one mesh of one material on the GPU (VegetationRenderer.cpp)
struct OcclusionRing;   // one distance ring of occlusion culling (OcclusionCuller.h)
class OcclusionCuller;
struct VegetationMesh;             // one mesh of one material on the GPU (VegetationRenderer.cpp)
class PointCloudRenderer;          // the `points` method (render/vegetation/PointCloudRenderer.h)
class DisplacedBillboardRenderer;  // `dmbbc` (render/vegetation/DisplacedBillboardRenderer.h)

struct VegetationSettings {
    VegetationMethod method = VegetationMethod::Lod;
    double quality = 1.0;          // > 1: finer levels (the error tolerated is divided by it)
    double minimumPixels = 1.5;    // plants smaller on screen are left to the terrain texture
    double maximumDistance = 0.0;  // metres; 0 = only minimumPixels limits
    double transitionBand = 0.35;  // screen-door fade width, in ln(error)
    bool closeUpMesh = true;       // hand over from the finest LoD to the source mesh
    float normalNoise = 0.6f;      // normal perturbation of ellipsoids (§3.4.1)
    // The plants' level-of-detail error in the shadow maps, in cascade texels (> 0): the
    // width of the shadow lookup's PCF box (shaders/shading/shadows.glsl), over which an
    // edge fades anyway. Plants cast down to minimumPixels / shadowErrorTexels texels.
    double shadowErrorTexels = 3.0;
    // Occlusion culling (issue 21, OcclusionCuller): the plants are drawn in rings of
    // distance, nearest first — up to occluderDistance, then each ring occlusionRingRatio
    // times as far, the last one unbounded — and before each ring the depth buffer (terrain,
    // meshes, the nearer rings) is read back into a hierarchical-Z pyramid against which
    // the ring's instances and instance tiles are culled. The image is the same as without
    // (only the order of equal-depth fragments may differ); off: one selection.
    bool occlusionCulling = true;
    double occluderDistance = 50.0;  // metres: the first ring
    double occlusionRingRatio = 4.0;
    int occlusionRings = 3;
    // The hand-over to the far-field canopy (FarFieldCanopy sets it per frame): trees drop
    // the pixels the canopy takes; disabled by default.
    FarFieldFade farField;
};

struct VegetationStatistics {
    std::size_t consideredInstances = 0;
    std::size_t visibleInstances = 0;
    std::size_t drawnInstances = 0;  // entries drawn (handover instances count twice)
    std::size_t drawCalls = 0;
    std::size_t ellipsoids = 0;  // primitives issued (prefixes × instances)
    std::size_t lines = 0;
    std::size_t quadPassRuns = 0;  // runs whose large ellipsoids needed the quad pass
    std::size_t meshInstances = 0;
    std::size_t billboardInstances = 0;
    std::size_t points = 0;    // point samples issued (the `points` method)
    double selectSeconds = 0;  // CPU: LodSelector::select
    double uploadSeconds = 0;  // CPU → GPU instance buffer
    // Occlusion culling: the instances culled (LodSelection::occludedInstances) and the
    // seconds of the depth read-backs and pyramids (a read-back first waits for what was
    // drawn before it to finish).
    std::size_t occludedInstances = 0;
    double occlusionSeconds = 0;
    // Shadow cascades drawShadow drew plants into since the last draw() (a cascade whose
    // depth ShadowMaps copied from its cache is not drawn).
    std::size_t shadowCascades = 0;
};

class VegetationRenderer : public ShadowCaster {
public:
    static Result<std::unique_ptr<VegetationRenderer>> create(const ShaderLibrary& library);
    ~VegetationRenderer() override;

    // Uploads one species; returns its index (species indices of batches refer to it).
    // Assets are kept alive by the renderer. Fails (the error names the plant), uploading
    // nothing, when the species would exceed LodSelector's limits: at most
    // LodSelector::kMaxSpecies species and kMaxBillboardLevels billboard levels each.
    Result<std::uint32_t> addSpecies(std::shared_ptr<const PlantAsset> asset,
                                     double transitionBand = VegetationSettings{}.transitionBand);
    std::size_t speciesCount() const { return species_.size(); }
    const std::vector<SpeciesLod>& speciesLods() const { return lods_; }
    // The asset of a species index (for the stream's name → index map).
    const std::shared_ptr<const PlantAsset>& asset(std::uint32_t species) const;

    // The season of each species (index as addSpecies returned; missing entries: full
    // leaf, green), applied by the following draws and shadow passes in the level of
    // detail itself: leaf ellipsoids keep a share leafFraction of their noise coverage
    // and turn towards the autumn colour; leaf triangles of the close-up and reference
    // mesh are dropped per triangle and recoloured. Lines (branches) are unchanged;
    // billboard clouds too (their texels mix leaves and branches).
    void setLeafStates(std::vector<LeafState> states);

    // Selects and draws `batches` into the bound G-buffer (depth test GREATER, reversed-Z,
    // depth writes on). `pixelsHigh`: the image height, for the pixel angle.
    void draw(const std::vector<const InstanceBatch*>& batches, const Camera& camera,
              const glm::dmat4& projection, double near, int pixelsWide, int pixelsHigh,
              const VegetationSettings& settings);

    // Shadow caster (seed 001 §7.1): the batches and settings of the last draw() (which
    // must still be alive) selected again for the cascade's orthographic box with
    // settings.shadowErrorTexels texels as the tolerated error; ellipsoids and lines
    // ray-cast along the light (shaders/shadows), with the LoD's noise alpha test (the
    // levels' ShadowThresholds) as the crown's transmittance; meshes and billboard clouds
    // alpha-tested. Skips the terrain-only cascade.
    void drawShadow(const ShadowView& view) override;
    // What drawShadow's depth depends on besides the cascade's box and the sun (which
    // ShadowMaps adds): the settings that select and draw, the species and their leaf
    // states, and each batch of the last draw() by its InstanceBatch::contentHash (set by
    // LodSelector::makeBatch; batches are not changed after it). Not the camera: the
    // selection is orthographic with a fixed error in texels, so it depends on the box
    // alone (the instances are drawn camera-relative, which moves a noise sample by less
    // than a millimetre: a few texels at a noise threshold may flip, the shade does not).
    std::optional<std::uint64_t> shadowCacheKey(const ShadowView& view) const override;

    const VegetationStatistics& statistics() const { return statistics_; }
    // The selection of the last draw() (with occlusion culling: of its farthest ring).
    const LodSelection& lastSelection() const { return selection_; }
    // The impostors method (VegetationMethod::Impostors): its settings and the last
    // frame's counts (single impostors, groups, group renders, validity tests).
    void setImpostorSettings(const ImpostorSettings& settings) { impostorSettings_ = settings; }
    const ImpostorStatistics& impostorStatistics() const { return impostors_->statistics(); }

private:
    VegetationRenderer() = default;
    struct Species;
    // Whether an ellipsoid of the run may need a sprite larger than the driver's largest
    // point (then the run is drawn a second time, as quads, for those ellipsoids).
    bool mayExceedPointSize(const DrawRun& run, double pixelAngle, double cornerTangent,
                            double near) const;
    void drawShadowRuns(const ShadowView& view, const VegetationSettings& settings);
    // Appends the species' per-ellipsoid shadow thresholds (core/plantlod/ShadowThresholds:
    // each level's thresholds for the leaves' coverage seen from 10° and 55°) and
    // re-uploads them.
    void appendShadowThresholds(const PlantAsset& asset);
    // drawRing's Mesh and Billboard runs (the source mesh and billboard-cloud levels).
    void drawMeshRuns(const glm::dmat4& projection, double near, int pixelsWide, int pixelsHigh,
                      const VegetationSettings& settings, bool handover);
    // The impostor captures of species not captured yet (on the impostors method's first use).
    Status captureImpostors();
    // uLeafFraction and uAutumn of `species` (full leaf when `leaves` is false).
    void setLeafUniforms(ShaderProgram& program, std::uint32_t species, bool leaves);
    // One selection and its draws (draw() runs one per occlusion ring): instances with
    // centres in (minimumDistance, maximumDistance] culled against `occlusion` (may be
    // null); statistics are added up.
    void drawRing(const std::vector<const InstanceBatch*>& batches, const Camera& camera,
                  const glm::dmat4& projection, double near, int pixelsWide, int pixelsHigh,
                  const VegetationSettings& settings, const OcclusionRing& ring);
    // The `dmbbc` method: the selection's Billboard runs as ray-marched boxes.
    void drawDisplacedBillboards(const glm::mat4& projection, double near, glm::vec2 viewport,
                                 float band);
    // The `points` method: the selection's Primitives runs as point clouds.
    void drawPoints(const glm::dmat4& projection, double near, int pixelsWide, int pixelsHigh,
                    double pixelAngle);
    // The impostors method's draw(): groups split off, the rest selected and drawn.
    void drawImpostors(const std::vector<const InstanceBatch*>& batches, const Camera& camera,
                       const glm::dmat4& projection, LodSelectionSettings selection);
    void drawMeshes(const std::vector<std::unique_ptr<VegetationMesh>>& meshes, const DrawRun& run,
                    glm::vec2 interval);

    ShaderProgram ellipsoidProgram_;
    ShaderProgram lineProgram_;
    ShaderProgram meshProgram_;
    ShaderProgram ellipsoidShadowProgram_;
    ShaderProgram lineShadowProgram_;
    std::vector<std::unique_ptr<Species>> species_;
    std::vector<SpeciesLod> lods_;
    GlBuffer ellipsoidBuffer_, lineBuffer_;  // all species, concatenated
    // The ellipsoids' noise thresholds in the shadow pass (ShadowThreshold low, high),
    // parallel to ellipsoidBuffer_.
    std::vector<glm::vec2> shadowThresholds_;
    GlBuffer shadowThresholdBuffer_;
    std::uint32_t ellipsoidCount_ = 0, lineCount_ = 0;
    GlBuffer instanceBuffer_;
    std::size_t instanceCapacity_ = 0;
    GlVertexArray primitiveArray_;   // instance attributes only
    float maximumPointSize_ = 1.0f;  // pixels: the driver's largest point sprite
    LodSelector selector_;           // its scratch is kept from frame to frame
    LodSelection selection_;
    // Occlusion culling: the depth read-back and its pyramid.
    std::unique_ptr<OcclusionCuller> occlusion_;
    // The shadow pass: the last draw()'s input, its own selector scratch and selection.
    std::vector<const InstanceBatch*> shadowBatches_;
    VegetationSettings shadowSettings_;
    LodSelector shadowSelector_;
    LodSelection shadowSelection_;
    VegetationStatistics statistics_;
    std::vector<LeafState> leafStates_;  // per species: the season of the render date
    std::unique_ptr<PointCloudRenderer> pointClouds_;
    std::unique_ptr<DisplacedBillboardRenderer> displacedBillboards_;
    std::vector<std::shared_ptr<const PlantAsset>> assets_;  // per species (the methods' input)
    std::unique_ptr<ImpostorRenderer> impostors_;
    bool impostorFailureReported_ = false;
    ImpostorSettings impostorSettings_;
};

}  // namespace sylva::render
