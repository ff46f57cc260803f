// TerrainRenderer: the spherical geometry-clipmap terrain (seed 001 ch. 5). Owns the
// static ring meshes, the CPU clipmaps of the height, colour and normal layers and
// their GPU texture arrays. update() brings the clipmaps to the camera (evaluating
// tiles through a TileProvider); draw() writes the G-buffer (albedo, normal, reversed-Z
// depth). Lighting happens in the ShadingPass, never here.
//
// Precision: positions are computed relative to the camera from float offsets that
// keep their relative precision (sylva::MapTransform), so 1.7 m eye height is stable
// anywhere on the globe; depth is reversed-Z with an infinite far plane.
//
// Needs a current GL 4.5 context for create(), update() and draw(); destroy it while
// that context is current.
#pragma once

#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include <glm/glm.hpp>

#include "sylva/core/base/Result.h"
#include "sylva/core/scene/Camera.h"
#include "sylva/core/sources/graph/SourceGraph.h"
#include "sylva/core/terrain/Clipmap.h"
#include "sylva/core/terrain/LevelVisibility.h"
#include "sylva/core/terrain/TerrainRings.h"
#include "sylva/render/gl/GlHandle.h"
#include "sylva/render/gl/ShaderLibrary.h"
#include "sylva/render/gl/ShaderProgram.h"
#include "sylva/render/shadows/ShadowCaster.h"
#include "sylva/render/terrain/ClipmapTexture.h"

namespace sylva::render {

struct TerrainSettings {
    int clipmapSize = 256;             // texels per clipmap level side (= tile size)
    int maxLevel = 24;                 // finest ring level
    int columns = 256;                 // bearing steps of the ring mesh
    int ringsPerLevel = 24;            // rings per level
    double maxTerrainHeight = 9000.0;  // metres, for the horizon safety margin
    // The G-buffer fragment shader (ShaderLibrary path); the far-field canopy draws the
    // same rings with its own (vegetation/farfield_canopy.frag).
    std::string fragmentShader = "terrain/terrain.frag";
    // Interactive updates (update() with waitForAll false) keep every clipmap level from
    // this one up to the finest wanted in the wanted list, so a coarse level is always
    // resident: after a jump the rings whose own level is not ready yet are drawn from the
    // finest ready one (never a hole), and only this root level is ever waited for (its
    // few tiles, once). -1: no root; nothing is waited for and update() returns an empty
    // range until the coarsest wanted level is ready (the far-field canopy, an overlay).
    int residentLevel = 0;
    // Added to the level as the tiles' priority (smaller first): the far-field canopy's
    // tiles come after the terrain's of the same level.
    int priorityOffset = 0;
};

struct TerrainFrameStatistics {
    LevelRange levels;      // levels drawn
    LevelRange wanted;      // levels the view asked for
    std::string degraded;   // why fewer levels were drawn than wanted (an error); empty if none
    int waitingLevel = -1;  // the first level not drawn because its tiles are still being produced
    // The finest clipmap level resident for the camera: rings finer than it sample it
    // (interactive frames after a jump; equals levels.finest otherwise).
    int textureLevel = -1;
    // The finest level brought up this frame with every coarser one (interactive: before
    // textureLevel is lowered to a level whose ground is below the camera). A camera the
    // viewer places stands on this level's ground, so textureLevel can follow it up: placed
    // on textureLevel instead, a walker on a hill stood under every finer level's ground
    // and textureLevel never rose (issue 20, the bench's "level 8 of 24").
    int residentLevel = -1;
    // Interactive frames whose camera is below the ground of every resident level (an
    // aircraft over a valley the coarse levels fill higher; issue 20's holes): the nadir
    // ceiling, metres (ellipsoid height) a little under the camera, at which the ground at
    // the nadir is capped, the cap rising 1:10 with the distance from it (terrain.vert).
    // None when the drawn ground under the camera is below it.
    std::optional<double> nadirCeiling;
    // Interactive frames: the ground drawn at the nadir, metres (ellipsoid height): the
    // textureLevel's, or the nadir ceiling; at least 1 m under the camera. The nadir probe
    // that sets the clearance (SceneRenderer::readyGround) may come from a finer level far
    // below it, so the near plane has to respect this one too (a 6.9 m near plane over
    // ground drawn 1.7 m under the camera showed the sky; the bench's descent, issue 20).
    // None for batch frames and unrooted renderers.
    std::optional<double> nadirGround;
    std::uint64_t triangles = 0;
    std::uint64_t uploadedBytes = 0;
    double updateSeconds = 0;  // CPU clipmap update including tile evaluation
};

class TerrainRenderer : public ShadowCaster {
public:
    static Result<std::unique_ptr<TerrainRenderer>> create(const ShaderLibrary& library,
                                                           const TerrainSettings& settings);
    ~TerrainRenderer() override;

    // The ring levels to draw for `camera` seen through `pixels` rows.
    LevelRange visibleLevels(const Camera& camera, double heightAboveTerrain, int pixels) const;

    // Brings the clipmap levels of `wanted` (and the one coarser, for blending) to
    // the camera's nadir, coarse to fine, as in seed 001 Algorithm 3 (§4.7): the tiles
    // of all levels are handed to the provider as the wanted list (priority = level,
    // so coarse first; stale queued tasks are cancelled), then each level is updated
    // from ready tiles only. A level is drawn as a ring only when all its layers are
    // ready; when a finer level's tiles are still pending (statistics().waitingLevel),
    // fail (a tile error) or the deadline passes, drawing stops at the last ready
    // level, whose fill disk then covers the nadir, so a missing level never leaves a
    // hole. `waitForAll` (batch rendering) waits for every level, so the image does not
    // depend on thread timing. Interactive (`waitForAll` false): nothing is waited for
    // but the resident root level (TerrainSettings::residentLevel); every wanted ring is
    // drawn, those finer than the finest resident level (statistics().textureLevel, at
    // most one whose ground under the camera is below it) from that level; when no resident
    // level's ground is below the camera, the ground near the nadir is capped under it
    // instead (statistics().nadirCeiling). Returns the
    // levels to draw (statistics().degraded says why fewer on error; empty, finest <
    // coarsest, only without a root), or the error when not even the coarsest level
    // could be made.
    Result<LevelRange> update(
        const TerrainLayers& layers, TileProvider& provider, const Camera& camera,
        const LevelRange& wanted,
        std::optional<std::chrono::steady_clock::time_point> deadline = std::nullopt,
        bool waitForAll = true);

    // Draws into the bound G-buffer (attachment 0: albedo, 1: normal; depth cleared
    // to 0 beforehand). `projection` is reversed-Z.
    void draw(const Camera& camera, const glm::dmat4& projection, const LevelRange& levels,
              bool ocean);

    // Shadow caster (seed 001 §7.1): the rings of the levels last drawn by draw(), seen from
    // the sun (depth only, orthographic), limited to the levels that reach the cascade and
    // no finer than its texels. Camera-relative like draw(), so the precision is the
    // G-buffer's. Draws every cascade, the terrain-only one included.
    void drawShadow(const ShadowView& view) override;
    // The state drawShadow's depth depends on besides the cascade's box and the sun: the
    // levels it draws, the resident level, the height source, the ocean clamp and the nadir
    // ceiling (with its nadir: while it is on, a moving camera redraws the terrain's
    // cascades). Not the camera otherwise: the rings follow it, but around any camera in
    // the box they triangulate the same heightfield (the clipmap holds the source's tiles)
    // at the same levels, no finer than the cascade's texels, so a moving camera keeps the
    // depth until its box moves.
    std::optional<std::uint64_t> shadowCacheKey(const ShadowView& view) const override;

    // By value: nadirCeiling is read from the ceiling draw() and shadowCacheKey() use, so
    // the report cannot disagree with what is drawn.
    TerrainFrameStatistics statistics() const;
    const TerrainSettings& settings() const { return settings_; }
    // The G-buffer program (fragmentShader), for a derived pass's own uniforms.
    ShaderProgram& gbufferProgram() { return program_; }

private:
    TerrainRenderer() = default;
    struct Mesh {
        GlVertexArray vertexArray;
        GlBuffer vertexBuffer;
        GlBuffer indexBuffer;
        std::int32_t indexCount = 0;
    };
    static Mesh upload(const TerrainMesh& mesh);
    // Sets the ring uniforms of `program` (terrain.vert) for `camera`, `rotation` (ECEF ->
    // the frame `projection` expects) and draws `levels` plus the fill disk; returns the
    // triangle count.
    // One clipmap layer (height, normals, colour) with its texture and source.
    struct LayerSlot {
        Clipmap* clipmap;
        ClipmapTexture* texture;
        const Source* source;
        int levelOffset;  // pyramid level = ring level - levelOffset
    };
    using LevelWindows = std::vector<std::pair<const LayerSlot*, ClipmapWindow>>;
    using ReadyTiles = std::map<std::pair<std::uint64_t, TileKey>, TilePointer>;
    // Looks up every tile of one level's `windows` (waiting for progress while some are
    // pending and `wait`), keeping them in `ready`; when none is pending, brings the
    // level's clipmaps to the windows and uploads the changed regions. Returns a tile's
    // or the update's error; `pending` says some tile is still being produced.
    Status bringUpLevel(int level, const LevelWindows& windows, TileProvider& provider, bool wait,
                        ReadyTiles& ready, bool& pending);
    // Interactive frames: the level to draw near the nadir, the finest resident one whose
    // ground under the camera is below it (standingLevel), else `resident`; sets
    // nadirCeiling_ when no such level's ground is clearly below the camera.
    int standOrCap(const Source& elevation, TileProvider& provider, const Camera& camera,
                   int resident, int blendLevel, int fallback);
    // Drops the clipmap levels of layers whose source changed (another scenario, an edit).
    void dropChangedSources(const TerrainLayers& layers);
    // The levels drawShadow draws into `view`'s cascade (none before the first draw()).
    std::optional<LevelRange> shadowLevels(const ShadowView& view) const;
    std::uint64_t drawRings(ShaderProgram& program, const Camera& camera,
                            const glm::dmat3& rotation, const glm::dmat4& projection,
                            const LevelRange& levels, bool ocean);

    TerrainSettings settings_;
    ShaderProgram program_;
    ShaderProgram shadowProgram_;           // terrain.vert + depth_only.frag
    std::optional<LevelRange> lastLevels_;  // of the last draw(), for the shadow casters
    bool lastOcean_ = true;
    Mesh ring_;
    Mesh fill_;
    std::unique_ptr<Clipmap> height_;
    std::unique_ptr<Clipmap> color_;
    std::unique_ptr<Clipmap> normals_;
    ClipmapTexture heightTexture_;
    ClipmapTexture colorTexture_;
    ClipmapTexture normalTexture_;
    int textureCeiling_ = 0;  // finest resident level of the last update (statistics)
    // The last update's nadir ceiling (statistics().nadirCeiling) and the camera's nadir it
    // is centred on (radians).
    struct NadirCeiling {
        double height = 0;  // metres, ellipsoid height
        double latitude = 0;
        double longitude = 0;
    };
    std::optional<NadirCeiling> nadirCeiling_;
    std::uint64_t sourceHashes_[3] = {0, 0, 0};  // height, normals, colour sources of the clipmaps
    bool hasColor_ = false;
    TerrainFrameStatistics statistics_;  // all but nadirCeiling (statistics() adds it)
    std::uint64_t uploadedBefore_ = 0;
};

}  // namespace sylva::render
