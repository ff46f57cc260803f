#include "GridElevationSource.h"

#include <algorithm>
#include <cmath>

#include "sylva/core/base/Hash.h"
#include "sylva/core/base/WorkerPool.h"

namespace sylva::bench {

double ElevationGrid::at(double latitude, double longitude, double outside) const {
    if (latitude < south || latitude > north || longitude < west || longitude > east) {
        return outside;
    }
    const double x = (longitude - west) / sampleSpacingLongitude();
    const double y = (north - latitude) / sampleSpacingLatitude();
    const int ix = std::min(static_cast<int>(x), width - 2);
    const int iy = std::min(static_cast<int>(y), height - 2);
    const double fx = x - ix, fy = y - iy;
    const float* row0 = heights.data() + std::size_t(iy) * width;
    const float* row1 = row0 + width;
    return (row0[ix] * (1 - fx) + row0[ix + 1] * fx) * (1 - fy) +
           (row1[ix] * (1 - fx) + row1[ix + 1] * fx) * fy;
}

GridElevationSource::GridElevationSource(std::string name, ElevationGrid grid, double outside)
    : Source(std::move(name), "grid", PortType::Elevation, 1),
      grid_(std::move(grid)),
      outside_(outside) {
    SYLVA_CHECK(grid_.width >= 2 && grid_.height >= 2 &&
                grid_.heights.size() == std::size_t(grid_.width) * grid_.height);
    ContentHash hash;
    hash.add(grid_.width)
        .add(grid_.height)
        .add(grid_.west)
        .add(grid_.south)
        .add(grid_.east)
        .add(grid_.north);
    hash.add(grid_.heights.data(), grid_.heights.size() * sizeof(float)).add(outside_);
    setParameterHash(hash.value());
}

Result<TilePointer> GridElevationSource::produce(const TileKey& key, TileProvider& provider) const {
    const TileFormat& format = provider.format();
    auto tile = std::make_shared<ImageTile>(key, format.size, format.border, 1);
    const int first = -format.border;
    WorkerPool::shared().run(format.size + 2 * format.border, [&](int row) {
        const int iy = first + row;
        const double latitude = tile->texelLatitude(iy);
        for (int ix = -format.border; ix < format.size + format.border; ++ix) {
            tile->at(ix, iy, 0) =
                static_cast<float>(grid_.at(latitude, tile->texelLongitude(ix), outside_));
        }
    });
    return TilePointer(std::move(tile));
}

}  // namespace sylva::bench
