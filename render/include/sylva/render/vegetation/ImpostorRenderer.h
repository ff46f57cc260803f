// ImpostorRenderer: the `impostors` vegetation method (issue 21) — multi-resolution
// view-direction billboards with group impostors (seed 004 §3.2–3.5) re-used while the
// two-level validity test of seed 000 ch. 7 holds.
//
// Per species (addSpecies): the source mesh is rendered, through the vegetation
// renderer's own mesh path, orthographically from the 17 directions of ImpostorViewSet
// at 64², 128² and 256² texels into three array textures per resolution: albedo
// (linear RGB, alpha = coverage), view normal (capture frame) and depth (the leaf's
// offset from the plane through the bounding-sphere centre). Captured once.
//
// Per frame (draw): instance batches (tiles) whose instances are all smaller than
// ImpostorSettings::groupPixels on screen and that the camera is outside of become
// group impostors: the tile's instance impostors rendered, from the current viewpoint,
// into a texture (albedo, normal, distance along the capture ray) that is drawn as one
// quad and re-used while ImpostorValidity says its parallax error is within
// groupErrorPixels pixels (and its texels are not magnified beyond 1.5×); otherwise it
// is rendered again (counted). The other instances arrive as a LodSelector selection
// (one transform per visible instance) and are drawn as single impostors: the view
// nearest to the direction toward the eye at the resolution that covers the plant's
// pixels, on a quad perpendicular to that view. Every fragment writes the G-buffer like
// the mesh path (albedo × tint, ambient occlusion 1, view normal facing the viewer) and
// the depth of the leaf it shows (gl_FragDepth), so impostors are depth-tested and
// shaded like the other paths.
//
// Frames: view space is camera-relative (metres, the camera's axes), reversed-Z depth
// with the infinite projection of SceneRenderer; group state is kept in the tile's frame
// (ECEF axes about the batch origin). Needs a current GL 4.5 context for every call;
// destroy it while that context is current. Errors come back as Result.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "sylva/core/base/Result.h"
#include "sylva/core/plantlod/ImpostorViewSet.h"
#include "sylva/core/scene/Camera.h"
#include "sylva/core/vegetation/ImpostorValidity.h"
#include "sylva/core/vegetation/LodSelector.h"
#include "sylva/render/gl/Framebuffer.h"
#include "sylva/render/gl/GlHandle.h"
#include "sylva/render/gl/ShaderLibrary.h"
#include "sylva/render/gl/ShaderProgram.h"

namespace sylva::render {

struct ImpostorSettings {
    // A tile is drawn as one group impostor when its largest plant is smaller than this
    // on screen (pixels) at the tile's nearest point; 0 disables group impostors.
    double groupPixels = 12.0;
    // The validity test's error angle, in pixels of the current view.
    double groupErrorPixels = 1.0;
    int largestGroupTexture = 1024;  // texels per side
};

struct ImpostorStatistics {
    std::size_t impostorInstances = 0;  // single impostors drawn
    std::size_t groups = 0;             // group impostors drawn
    std::size_t groupInstances = 0;     // instances the groups stand for
    std::size_t groupsRendered = 0;     // group textures (re)rendered this frame
    std::size_t resolutionRenders = 0;  // of those: because the texels were too coarse
    ImpostorValidityCounters validity;  // two-level tests of this frame
};

class ImpostorRenderer {
public:
    // Draws the species' source mesh once, transformed by `instance`, with `projection`
    // into the bound framebuffer (the caller's mesh path).
    using ModelDrawer =
        std::function<void(const DrawInstance& instance, const glm::mat4& projection)>;

    static Result<std::unique_ptr<ImpostorRenderer>> create(const ShaderLibrary& library);
    ~ImpostorRenderer();

    // Captures species number `species` (must be the next index) with bounding sphere
    // `lod.sphereCenter`, `lod.sphereRadius` (model frame) through `drawModel`. Restores
    // the framebuffer binding, viewport and clip control. Fails when a capture target
    // cannot be created.
    Status addSpecies(std::uint32_t species, const SpeciesLod& lod, const ModelDrawer& drawModel);
    // Species captured so far (addSpecies is called in species order).
    std::size_t speciesCount() const { return species_.size(); }

    // Splits `batches` into tiles drawn as group impostors (kept by the renderer for this
    // frame) and the rest (returned) for the caller's selection. `selection` carries the
    // frustum and pixel angle of the view.
    std::vector<const InstanceBatch*> partition(const std::vector<const InstanceBatch*>& batches,
                                                const Camera& camera,
                                                const LodSelectionSettings& selection,
                                                const ImpostorSettings& settings);

    // Draws the single impostors of `selected` (Mesh runs: one transform per instance)
    // and the group impostors of the last partition() into the bound G-buffer.
    void draw(const LodSelection& selected, const std::vector<SpeciesLod>& lods,
              const Camera& camera, const glm::dmat4& projection, double pixelAngle,
              const ImpostorSettings& settings);

    const ImpostorStatistics& statistics() const { return statistics_; }

private:
    ImpostorRenderer() = default;
    struct SpeciesAtlas;
    struct Group;
    struct GpuImpostor;
    void appendImpostor(std::vector<std::vector<GpuImpostor>>& byLevel,
                        const DrawInstance& instance, const SpeciesLod& lod, std::uint32_t species,
                        double pixelAngle) const;
    void drawImpostors(const std::vector<std::vector<GpuImpostor>>& byLevel,
                       const glm::mat4& projection, bool writeDistance);
    Status renderGroup(Group& group, const InstanceBatch& batch,
                       const std::vector<SpeciesLod>& lods, const Camera& camera, int texels,
                       const ImpostorValidity& validity);
    void drawGroup(const Group& group, const InstanceBatch& batch, const Camera& camera,
                   const glm::mat4& projection);

    ShaderProgram impostorProgram_;
    ShaderProgram groupProgram_;
    ImpostorViewSet views_ = ImpostorViewSet::upperHemisphere();
    std::vector<std::unique_ptr<SpeciesAtlas>> species_;
    GlBuffer impostorBuffer_;
    std::size_t impostorCapacity_ = 0;
    GlVertexArray emptyArray_;
    // Group impostors by tile (keyed by the batch's address and origin), with the frame
    // they were last drawn in; the ones of this frame's partition.
    std::map<const InstanceBatch*, std::unique_ptr<Group>> groups_;
    std::vector<const InstanceBatch*> groupedBatches_;
    std::uint64_t frame_ = 0;
    ImpostorStatistics statistics_;
};

}  // namespace sylva::render
