// ScreeningSurface: the surface that blocks sight lines in a screened ZTV, a digital
// surface model made on the analysis grid as the bare earth plus the screens:
//   - buildings: polygons of an OGR data set (any CRS; reprojected to the grid's) with a
//     numeric height attribute in metres above the ground (default `height`, the
//     convention of the `buildings` source); a cell is covered when its centre lies in
//     the polygon (GDAL's rasterizer, default rule); where footprints overlap the
//     tallest wins;
//   - canopy: a canopy height raster (metres above the ground; no-data and negative
//     values are open ground), resampled bilinearly at the cell centres; it must share
//     the DEM's CRS;
//   - plants: the crowns of a `plants` source (PlantCrowns), each a column of the tree's
//     height over the cells whose centre lies within its crown radius (at least the
//     cell holding the stem), the tallest crown winning; they count as canopy.
// surface = ground + max(building, canopy) per cell. No-data ground stays no-data.
//
// Failures (Result errors naming the file and the reason): an unreadable data set, a
// missing or non-numeric height field, a feature whose height is missing or not
// positive (named by its FID), a geometry that cannot be reprojected, a canopy raster
// in another CRS or not covering the grid.
#pragma once

#include <span>
#include <string>

#include "sylva/core/analysis/ElevationGrid.h"
#include "sylva/core/analysis/PlantCrowns.h"
#include "sylva/core/base/Result.h"

namespace sylva {

struct ScreenLayer {
    enum class Kind { Buildings, Canopy, Plants };
    Kind kind = Kind::Buildings;
    std::string path;                        // vector data set (buildings) or raster (canopy)
    std::string heightAttribute = "height";  // buildings: the field with the height, metres
    std::string layer;                       // buildings: layer name; empty: the first layer
    std::vector<PlantCrown> crowns;          // plants: x, y in the grid's CRS
};

struct ScreeningSurface {
    ElevationGrid surface;          // ground + screens
    std::size_t buildingCells = 0;  // cells covered by a building
    std::size_t canopyCells = 0;    // cells with canopy > 0 (and no taller building)
};

Result<ScreeningSurface> buildScreeningSurface(const ElevationGrid& ground,
                                               std::span<const ScreenLayer> layers);

}  // namespace sylva
