// FeatureSource (`source x : features`): vector data from an OGR data set (Shapefile,
// GeoJSON, GeoPackage, KML ...): one layer, optionally filtered by an OGR SQL
// attribute filter (`where`), reprojected to WGS84 longitude/latitude (radians).
//
// Access path. Features do not flow through the image-tile caches: produce() fails
// (a features source has no raster tiles). A consumer (rasterize, elevation_edit,
// plants) keeps its input as `const Source*`, checks output() == PortType::Features,
// casts to FeatureSource and calls collection() once per produce(), then
// collection.query(window) for the features over its tile (with the longitude
// shift that puts antimeridian-crossing features over the window).
//
// Loading is lazy (on the first collection() call) and happens once per content
// hash in the process: sources with equal hashes (the same file, layer, filter and
// file modification time, e.g. in two scenarios) share one FeatureCollection through
// a process-wide registry guarded by a mutex; the load itself runs under a
// per-hash mutex, so concurrent first calls wait for one load. A failed load is
// remembered and the same error returned on every call (one message naming the
// file, layer, field or feature and the reason).
#pragma once

#include <filesystem>
#include <memory>
#include <mutex>

#include "sylva/core/sources/Source.h"
#include "sylva/core/sources/SourceBuildContext.h"
#include "sylva/core/sources/vector/FeatureCollection.h"

namespace sylva {

class FeatureSource final : public Source {
public:
    FeatureSource(std::string name, std::filesystem::path file, FeatureLoadOptions options);

    static Result<std::unique_ptr<Source>> create(const SourceBuildContext& context);

    // Always an error: features are not raster tiles (see above).
    Result<TilePointer> produce(const TileKey& key, TileProvider& provider) const override;

    // The loaded collection (loads it on the first call; thread-safe).
    Result<std::shared_ptr<const FeatureCollection>> collection() const;

    // `source` as a FeatureSource when it gives features, else nullptr.
    static const FeatureSource* from(const Source* source);

    const std::filesystem::path& file() const { return file_; }

    struct LoadSlot;  // shared per content hash (FeatureSource.cpp)

private:
    std::filesystem::path file_;
    FeatureLoadOptions options_;
    std::shared_ptr<LoadSlot> slot_;
};

}  // namespace sylva
