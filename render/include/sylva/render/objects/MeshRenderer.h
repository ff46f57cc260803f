// MeshRenderer: the proposal's buildings and placed models (MeshSource tiles) on the GPU,
// drawn into the G-buffer after the terrain (reversed-Z depth test GREATER, so terrain
// and plants hide them and they hide what is behind), lit by the shading pass like the
// terrain.
//
// Streaming: update() keeps the tiles (MeshSource::kTileLevel) within
// MeshSettings::maximumDistance of the camera resident, building missing ones through the
// provider (the sources' elevation). Tiles not wanted by this update (out of range, or
// another scenario's) stay resident, not drawn, while their geometry stays within
// MeshSettings::keptBytes (beyond it, those wanted longest ago go first): scenario
// comparisons draw several scenarios in turn and flights come back, and rebuilding a
// city at each switch cost minutes a frame. Models are uploaded once per MeshModel and
// drawn instanced: one draw per model part, level of detail and tile. Level of detail:
// each placement draws each part at the coarsest simplified level (ModelPart::levels,
// OpenMesh's quadric decimation) whose geometric error, scaled by the placement,
// projects below half a pixel at its distance (full detail for views without a pixel
// angle, such as the shadow maps).
//
// Precision: every tile and placement is transformed relative to the eye in double on the
// CPU (as InstanceBatch does for plants); the GPU sees float offsets of at most the view
// distance. Culling: tiles and placements by bounding sphere against the frustum, and
// placements smaller than MeshSettings::minimumPixels.
//
// Textures: a part with a base colour texture (ModelPart::texture) is drawn with it bound
// (unit 0, mipmapped: the texture's colour times the vertex colour); buildings have none.
//
// Depth-only reuse (shadow maps): draw() takes any MeshDrawView (an orthographic light
// view as well as the camera) and a depth-only flag, which draws positions only, with no
// colour outputs, into whatever framebuffer is bound.
//
// Needs a current GL 4.5 context for create(), update() and draw(); destroy it while that
// context is current.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "sylva/core/base/Result.h"
#include "sylva/core/scene/Camera.h"
#include "sylva/core/sources/objects/MeshSource.h"
#include "sylva/render/gl/GlHandle.h"
#include "sylva/render/gl/ShaderLibrary.h"
#include "sylva/render/gl/ShaderProgram.h"
#include "sylva/render/shadows/ShadowCaster.h"

namespace sylva::render {

// How a pass sees the world: an ECEF point p goes to clip space as
// projection * vec4(rotation * (p - eye), 1); the difference is taken in double.
struct MeshDrawView {
    glm::dvec3 eye{0.0};         // ECEF metres: the camera (or the light frustum's origin)
    glm::dmat3 rotation{1.0};    // ECEF → view space (x right, y up, z backwards)
    glm::dmat4 projection{1.0};  // view → clip: reversed-Z perspective, or orthographic
    double pixelAngle = 0.0;     // radians per pixel at the centre; 0: no size culling
};

struct MeshSettings {
    double maximumDistance = 20000.0;  // metres: tiles farther from the camera are not drawn
    double minimumPixels = 1.0;        // placements smaller on screen are skipped
    // Bytes of geometry (vertices, indices, placements) of tiles kept though not wanted
    // by the update (the 100,000-building benchmark city: 1.13 million triangles, at most
    // about 140 MB).
    std::size_t keptBytes = std::size_t(512) << 20;
};

struct MeshStatistics {
    std::size_t residentTiles = 0;
    std::size_t tilesBuilt = 0;       // in the last update
    double buildSeconds = 0.0;        // building and uploading them
    std::size_t tilesDrawn = 0;       // in the last draw
    std::size_t placementsDrawn = 0;  // model placements
    std::size_t trianglesDrawn = 0;
};

struct MeshGpuGeometry;  // buffers of one MeshGeometry (MeshRenderer.cpp)

class MeshRenderer : public ShadowCaster {
public:
    static Result<std::unique_ptr<MeshRenderer>> create(const ShaderLibrary& library);
    ~MeshRenderer();

    // Makes the tiles of `sources` near the camera resident. Fails with the source's error
    // (a bad feature, an unreadable model, a failed elevation tile).
    Status update(const std::vector<const MeshSource*>& sources, TileProvider& provider,
                  const Camera& camera, const MeshSettings& settings);

    // Draws the tiles of the last update's sources with the current framebuffer, depth test and
    // viewport; sets and restores its own depth state (GREATER, writes on).
    void draw(const MeshDrawView& view, bool depthOnly);
    // Depth of the resident tiles into one shadow cascade (ShadowCaster.h: the sun's
    // orthographic view, depth test LESS); skips the terrain-only cascade.
    void drawShadow(const ShadowView& view) override;

    const MeshStatistics& statistics() const { return statistics_; }
    // The tiles of the last update's sources near its camera (those draw() draws): the
    // CPU geometry, shared, for collisions (core/sources/objects/MeshCollision).
    std::vector<std::shared_ptr<const MeshTile>> shownTiles() const;

private:
    struct ResidentTile;
    MeshRenderer() = default;
    struct ModelEntry;
    // The model's GPU geometry and textures, uploaded on first use.
    const ModelEntry& modelEntry(const std::shared_ptr<const MeshModel>& model);
    void drawModel(const ResidentTile& tile, const MeshDrawView& view, bool depthOnly);
    // draw() with `depthFunction` (GL_GREATER for the reversed-Z camera, GL_LESS for shadows).
    void drawWithDepthTest(const MeshDrawView& view, bool depthOnly, unsigned depthFunction);

    ShaderProgram meshProgram_, depthProgram_;
    GlBuffer instanceBuffer_;
    std::size_t instanceCapacity_ = 0;
    std::vector<float> instanceScratch_;
    // Drops tiles not wanted by the current update beyond `keptBytes` bytes, those
    // wanted longest ago first.
    void dropKeptTiles(std::size_t keptBytes);
    std::uint64_t updates_ = 0;
    // Resident tiles by (source content hash, key).
    std::map<std::pair<std::uint64_t, TileKey>, std::unique_ptr<ResidentTile>> tiles_;
    // Uploaded models; the shared pointer keeps the address from being reused.
    struct ModelEntry {
        std::shared_ptr<const MeshModel> model;
        // Per part: the full geometry, then its simplified levels (ModelPart::levels).
        std::vector<std::vector<std::unique_ptr<MeshGpuGeometry>>> parts;
        // MeshModel::textures as sRGB8_ALPHA8 textures with full mipmap chains (repeat,
        // trilinear), sampled by objects/mesh.frag.
        std::vector<GlTexture> textures;
    };
    std::map<const MeshModel*, ModelEntry> models_;
    MeshStatistics statistics_;
};

}  // namespace sylva::render
