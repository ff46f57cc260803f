// GridElevationSource: elevation from an in-memory regular longitude/latitude grid
// (row 0 at the north edge), bilinear between grid points, `outside` metres beyond
// the grid. Not a project-file kind: benchmarks and tests use it to feed the clipmap
// and a brute-force mesh from exactly the same DEM.
#pragma once

#include <vector>

#include "sylva/core/sources/Source.h"

namespace sylva::bench {

struct ElevationGrid {
    int width = 0;                                    // samples per row
    int height = 0;                                   // rows
    double west = 0, south = 0, east = 0, north = 0;  // radians; samples at the corners
    std::vector<float> heights;                       // metres, width * height, row-major

    double sampleSpacingLongitude() const { return (east - west) / (width - 1); }
    double sampleSpacingLatitude() const { return (north - south) / (height - 1); }
    // Bilinear height at (latitude, longitude), or `outside` beyond the grid.
    double at(double latitude, double longitude, double outside) const;
};

class GridElevationSource final : public Source {
public:
    GridElevationSource(std::string name, ElevationGrid grid, double outside);

    Result<TilePointer> produce(const TileKey& key, TileProvider& provider) const override;
    const ElevationGrid& grid() const { return grid_; }

private:
    ElevationGrid grid_;
    double outside_;
};

}  // namespace sylva::bench
