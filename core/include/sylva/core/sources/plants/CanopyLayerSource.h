// CanopyLayerSource: the far-field canopy's clipmap layers, built by the renderer (not a
// project-language kind) from the scenario's terrain elevation and its plants sources.
//  - Elevation: the combined elevation map of seed 000 ch. 6, CEM = terrain height +
//    canopy height (CanopyProfile: proxy height × cover from the density mask), metres
//    above the WGS84 ellipsoid, one channel. Where several plants sources overlap, the
//    tallest canopy wins.
//  - Cover: RGBA, linear RGB albedo of the winning source's canopy and its cover [0, 1] in
//    alpha (0: no forest, the far-field shader discards there so the terrain shows).
// Texels are evaluated on the tile's own grid: the density mask is asked for the same
// key as the elevation, so both layers are band-limited like every other clipmap layer
// (a coarse texel carries the mask's mean over its footprint).
//
// Plants sources that scatter from polygons only (no `density`) contribute no canopy
// (not built: their polygons would need the coverage rasterizer here).
// produce() fails when an input tile fails (the error names this source).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "sylva/core/sources/Source.h"
#include "sylva/core/sources/plants/CanopyProfile.h"

namespace sylva {

enum class CanopyLayer { Elevation, Cover };

struct CanopyStand {
    const Source* density = nullptr;  // mask, one channel in [0, 1]; not owned
    CanopyProfile profile;
};

class CanopyLayerSource final : public Source {
public:
    // `elevation` is the terrain's; `stands` must not be empty and every density non-null.
    CanopyLayerSource(std::string name, CanopyLayer layer, const Source* elevation,
                      std::vector<CanopyStand> stands);

    Result<TilePointer> produce(const TileKey& key, TileProvider& provider) const override;

private:
    CanopyLayer layer_;
    const Source* elevation_;
    std::vector<CanopyStand> stands_;
};

}  // namespace sylva
