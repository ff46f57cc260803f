#include "sylva/core/sources/objects/MeshSource.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "sylva/core/sources/vector/FeatureSource.h"

namespace sylva {

Result<MeshInputs> readMeshInputs(const SourceBuildContext& context) {
    const BlockReader& reader = context.reader;
    Result<const Source*> features = context.input("features", true);
    if (!features) {
        return features.error();
    }
    MeshInputs inputs;
    inputs.features = FeatureSource::from(features.value());
    if (inputs.features == nullptr) {
        return Error{reader.where("features") + "'features' must be a features source"};
    }
    Result<const Source*> elevation = context.input("elevation", true);
    if (!elevation) {
        return elevation.error();
    }
    if (elevation.value()->output() != PortType::Elevation) {
        return Error{reader.where("elevation") + "'elevation' must be an elevation, but source '" +
                     elevation.value()->name() + "' gives " +
                     portTypeName(elevation.value()->output())};
    }
    inputs.elevation = elevation.value();
    return inputs;
}

MeshSource::MeshSource(std::string name, std::string kind)
    : Source(std::move(name), std::move(kind), PortType::Meshes, 0) {}

Result<TilePointer> MeshSource::produce(const TileKey& key, TileProvider&) const {
    return Error{"source '" + name() + "' (" + kind() + ") gives meshes, not raster tiles (tile " +
                 key.toString() + ")"};
}

TileKey MeshSource::keyOf(const glm::dvec2& point) {
    const double pi = std::numbers::pi;
    const int columns = TileKey::columns(kTileLevel, 0), rows = TileKey::rows(kTileLevel);
    double u = (point.x + pi) / (2 * pi);
    u -= std::floor(u);
    const int x = std::clamp(static_cast<int>(u * columns), 0, columns - 1);
    const int y = std::clamp(static_cast<int>((pi / 2 - point.y) / pi * rows), 0, rows - 1);
    return TileKey{kTileLevel, 0, x, y};
}

const MeshSource* MeshSource::from(const Source* source) {
    if (source == nullptr || source->output() != PortType::Meshes) {
        return nullptr;
    }
    return dynamic_cast<const MeshSource*>(source);
}

}  // namespace sylva
