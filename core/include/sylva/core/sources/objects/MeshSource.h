// MeshSource: a source of 3D geometry on the terrain (kinds `buildings` and `objects`,
// port type `meshes`): the proposal of a scenario, drawn by the mesh renderer when a
// scenario lists it in its `layers`.
//
// Access path. Meshes are not image tiles: produce() fails. The renderer casts with
// MeshSource::from() and asks tile(key, provider) for tiles of level kTileLevel
// (longitude reduction 0) that intersect bounds(); the provider serves the source's
// elevation input. Every tile is a pure function of the key, the inputs and the
// parameters; a feature belongs to the one tile that holds its reference point
// (buildings: the mean of the outer ring's vertices; objects: the placement).
//
// Errors. The first call of bounds() or tile() checks every feature (kind, attributes,
// geometry) and fails with "<file>: feature <id>: <reason>"; that result is remembered,
// so either everything is drawn or nothing (no half-drawn proposal).
#pragma once

#include <memory>
#include <string>

#include "sylva/core/base/Result.h"
#include "sylva/core/sources/Source.h"
#include "sylva/core/sources/SourceBuildContext.h"
#include "sylva/core/sources/objects/MeshTile.h"
#include "sylva/core/sources/vector/FeatureCollection.h"

namespace sylva {

class FeatureSource;

// The two inputs every mesh kind reads: `features` (a features source) and `elevation`
// (an elevation source, for the ground under each feature). Fails with the block's
// location when either is missing or of another kind.
struct MeshInputs {
    const FeatureSource* features = nullptr;
    const Source* elevation = nullptr;
};
Result<MeshInputs> readMeshInputs(const SourceBuildContext& context);

class MeshSource : public Source {
public:
    // About 1.2 km (180° / 2^14) tiles: a city streams in a few dozen tiles around the
    // camera, and float offsets from a tile's origin stay well below a millimetre.
    static constexpr int kTileLevel = 14;
    // The pyramid level whose elevation grid heights are sampled from (texels of about
    // 1.2 m): finer than any DEM the projects use, coarse enough to be cheap.
    static constexpr int kGroundLevel = 16;

    MeshSource(std::string name, std::string kind);

    // Always an error: meshes are not raster tiles.
    Result<TilePointer> produce(const TileKey& key, TileProvider& provider) const override;

    // Geographic bounds of every feature (radians); fails as described above.
    virtual Result<GeographicBounds> bounds() const = 0;
    // The geometry of tile `key` (level kTileLevel); an empty tile when nothing is there.
    virtual Result<std::shared_ptr<const MeshTile>> tile(const TileKey& key,
                                                         TileProvider& provider) const = 0;

    // The key of level kTileLevel holding (longitude, latitude) radians (any longitude).
    static TileKey keyOf(const glm::dvec2& longitudeLatitude);

    // `source` as a MeshSource when it gives meshes, else nullptr.
    static const MeshSource* from(const Source* source);
};

}  // namespace sylva
