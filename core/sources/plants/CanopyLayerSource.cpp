#include "sylva/core/sources/plants/CanopyLayerSource.h"

#include <algorithm>

#include "sylva/core/base/Hash.h"

namespace sylva {

CanopyLayerSource::CanopyLayerSource(std::string name, CanopyLayer layer, const Source* elevation,
                                     std::vector<CanopyStand> stands)
    : Source(std::move(name), layer == CanopyLayer::Elevation ? "canopy_elevation" : "canopy_cover",
             layer == CanopyLayer::Elevation ? PortType::Elevation : PortType::Image,
             layer == CanopyLayer::Elevation ? 1 : 4),
      layer_(layer),
      elevation_(elevation),
      stands_(std::move(stands)) {
    SYLVA_CHECK(elevation != nullptr && !stands_.empty());
    addInput(elevation);
    ContentHash hash;
    hash.add(int(layer));
    for (const CanopyStand& stand : stands_) {
        SYLVA_CHECK(stand.density != nullptr);
        addInput(stand.density);
        const CanopyProfile& p = stand.profile;
        hash.add(p.height()).add(p.crownWidth()).add(p.stemsPerSquareMetre());
        hash.add(p.albedo().r).add(p.albedo().g).add(p.albedo().b);
    }
    setParameterHash(hash.value());
}

Result<TilePointer> CanopyLayerSource::produce(const TileKey& key, TileProvider& provider) const {
    const TileFormat& format = provider.format();
    auto tile = std::make_shared<ImageTile>(key, format.size, format.border, channels());
    TilePointer ground;
    if (layer_ == CanopyLayer::Elevation) {
        Result<TilePointer> elevation = provider.tile(*elevation_, key);
        if (!elevation) {
            return Error{name() + ": " + elevation.error().message};
        }
        ground = elevation.value();
    }
    std::vector<TilePointer> densities;
    for (const CanopyStand& stand : stands_) {
        Result<TilePointer> density = provider.tile(*stand.density, key);
        if (!density) {
            return Error{name() + ": " + density.error().message};
        }
        densities.push_back(density.value());
    }
    for (int iy = -format.border; iy < format.size + format.border; ++iy) {
        for (int ix = -format.border; ix < format.size + format.border; ++ix) {
            double height = 0.0, cover = 0.0;
            const CanopyStand* winner = &stands_.front();
            for (std::size_t s = 0; s < stands_.size(); ++s) {
                const double density = densities[s]->at(ix, iy, 0);
                const double h = stands_[s].profile.canopyHeight(density);
                if (h > height) {
                    height = h;
                    cover = stands_[s].profile.cover(density);
                    winner = &stands_[s];
                }
            }
            if (layer_ == CanopyLayer::Elevation) {
                tile->at(ix, iy, 0) = float(ground->at(ix, iy, 0) + height);
            } else {
                const glm::dvec3& albedo = winner->profile.albedo();
                tile->at(ix, iy, 0) = float(albedo.r);
                tile->at(ix, iy, 1) = float(albedo.g);
                tile->at(ix, iy, 2) = float(albedo.b);
                tile->at(ix, iy, 3) = float(cover);
            }
        }
    }
    return TilePointer(std::move(tile));
}

}  // namespace sylva
