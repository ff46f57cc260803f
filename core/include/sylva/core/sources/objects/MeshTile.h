// MeshTile: the drawable geometry of the proposal (buildings, placed models) in one tile
// of the pyramid, as a MeshSource gives it to the renderer.
//
// Precision: positions are float offsets from a double ECEF origin per tile (a tile of
// level MeshSource::kTileLevel is about 1.2 km wide, so float offsets keep ~0.1 mm), and
// the renderer subtracts the camera in double, as InstanceBatch does for plants.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "sylva/core/tiles/TileKey.h"

namespace sylva {

// One vertex: position (metres, frame of its owner: tile ECEF offsets for buildings, the
// model frame for model parts), unit normal in the same frame, colour as packed sRGB8
// RGBA (r in the lowest byte; alpha unused, 255), texture coordinates of its part's
// texture (glTF convention: u right, v down from the image's first row; repeating; unused
// without a texture). The colour multiplies the texture (glTF's baseColorFactor).
struct MeshVertex {
    glm::vec3 position{0.0f};
    glm::vec3 normal{0.0f, 0.0f, 1.0f};
    std::uint32_t color = 0xffffffffu;
    glm::vec2 uv{0.0f};
};
static_assert(sizeof(MeshVertex) == 36);

// Indexed triangles, counter-clockwise seen from outside.
struct MeshGeometry {
    std::vector<MeshVertex> vertices;
    std::vector<std::uint32_t> indices;
    bool empty() const { return indices.empty(); }
};

// One named node of an imported model with the triangles it owns. `local` maps the
// part's frame into its parent's (or the model frame for roots); the model frame is
// metres, +Z up, +Y forward (glTF's +Y up is converted on import). An articulated part
// turns about `axis` of its own frame (glTF nodes: +Y, the node's up; OBJ groups: +Z),
// counter-clockwise seen from the axis tip, by the placement's angle for it.
// A simplified copy of a part's geometry (MeshSimplifier) for drawing it small:
// `errorMetres` bounds the distance of the original's vertices from it (model frame, before
// the placement's scale), so it may be drawn when that error projects below half a pixel.
struct SimplifiedGeometry {
    MeshGeometry geometry;
    double errorMetres = 0.0;
};

// A base colour texture: sRGB8-encoded RGBA (alpha linear), rows top to bottom (glTF's v = 0
// is the first row), width * height * 4 bytes. (Not sylva::Image: this header is included
// where `using namespace render` would make that name ambiguous with render::Image.)
struct MeshTexture {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> pixels;
};

struct ModelPart {
    std::string name;
    int parent = -1;  // index into MeshModel::parts (always smaller than this part's)
    glm::dmat4 local{1.0};
    glm::dvec3 axis{0.0, 0.0, 1.0};  // unit, in the part's frame
    MeshGeometry geometry;
    std::vector<SimplifiedGeometry> levels;  // ever coarser, ever larger error; may be empty
    int texture = -1;  // index into MeshModel::textures of the base colour texture, -1: none
};

struct MeshModel {
    std::string file;              // as given, for messages
    std::vector<ModelPart> parts;  // parents before children
    // Base colour textures (sRGB8 RGBA, rows top to bottom), shared by the parts naming them.
    // A node whose primitives use several textures is split on import: the triangles of
    // its first texture stay in the part, the others become child parts named
    // "<node>#<k>" with the identity transform (they follow the node's articulation).
    std::vector<MeshTexture> textures;
    glm::dvec3 boundsCenter{0.0};  // model frame, unarticulated
    double boundsRadius = 0.0;     // sphere holding every articulation (metres)
    std::size_t triangleCount() const;
    // Index of the part named `name`, or -1.
    int findPart(const std::string& name) const;
    // The part transforms (model frame) with part i turned by angles[i] radians about its
    // axis (angles may be shorter than parts: missing angles are 0).
    std::vector<glm::dmat4> partTransforms(const std::vector<float>& angles) const;
};

// One placed model: model frame → ECEF is position + axes * p (axes include heading,
// the local east/north/up frame and the scale).
struct ModelPlacement {
    glm::dvec3 position{0.0};  // ECEF metres
    glm::dmat3 axes{1.0};
    std::vector<float> partAngles;  // radians per part (see ModelPart); may be empty
    std::int64_t featureId = -1;    // -1: an explicit position
};

struct MeshTile {
    TileKey key;
    glm::dvec3 origin{0.0};                  // ECEF metres; geometry positions are offsets from it
    MeshGeometry geometry;                   // static triangles (buildings), normals in ECEF
    std::shared_ptr<const MeshModel> model;  // with placements (objects)
    std::vector<ModelPlacement> placements;
    glm::dvec3 boundsCenter{0.0};  // ECEF sphere around everything in the tile
    double boundsRadius = 0.0;
    std::size_t featureCount = 0;  // buildings or placements in the tile
    bool empty() const { return geometry.empty() && placements.empty(); }
};

}  // namespace sylva
