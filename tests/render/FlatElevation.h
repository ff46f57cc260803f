// Test elevation source: sea level (0 m) everywhere, so the surface is the ellipsoid.
#pragma once

#include <algorithm>
#include <memory>
#include <string_view>

#include "sylva/core/base/Hash.h"
#include "sylva/core/sources/Source.h"
#include "sylva/core/tiles/ImageTile.h"

namespace sylva::render {

class FlatElevation final : public Source {
public:
    FlatElevation() : Source("flat", "test", PortType::Elevation, 1) {
        setParameterHash(ContentHash().add(std::string_view("flat-v1")).value());
    }
    Result<TilePointer> produce(const TileKey& key, TileProvider& provider) const override {
        const TileFormat& format = provider.format();
        auto tile = std::make_shared<ImageTile>(key, format.size, format.border, 1);
        std::fill(tile->texels().begin(), tile->texels().end(), 0.0f);
        return TilePointer(tile);
    }
};

}  // namespace sylva::render
