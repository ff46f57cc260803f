// NormalMapSource (`source x : normal_map`): metric surface normals from elevation
// (seed 001 §4.4.1 item 5). Central differences over the height tile's border give
// east and north slopes in metres per metre on the WGS84 ellipsoid (east spacing
// N(lat) cos(lat) dlon, north spacing M(lat) dlat), so normals are right at any
// latitude and seamless across tiles. Output: ECEF unit vectors (3 channels); the
// outermost border ring uses one-sided differences.
#pragma once

#include <glm/glm.hpp>

#include "sylva/core/sources/Source.h"
#include "sylva/core/sources/SourceBuildContext.h"

namespace sylva {

class NormalMapSource final : public Source {
public:
    NormalMapSource(std::string name, const Source* height, double exaggeration);

    // From a `source x : normal_map` block.
    static Result<std::unique_ptr<Source>> create(const SourceBuildContext& context);

    Result<TilePointer> produce(const TileKey& key, TileProvider& provider) const override;

    // ECEF unit normal at texel (ix, iy) of an elevation tile; ix, iy may lie in the
    // border. Slopes are multiplied by `exaggeration`.
    static glm::dvec3 normalAt(const ImageTile& height, int ix, int iy, double exaggeration);

private:
    const Source* height_;
    double exaggeration_;
};

}  // namespace sylva
