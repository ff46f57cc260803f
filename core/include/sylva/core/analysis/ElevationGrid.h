// ElevationGrid: a north-up raster of terrain heights in a projected CRS, the input of
// the visibility analyses (core/analysis). Cell (col, row) covers
// [originX + col·cellWidth, originX + (col+1)·cellWidth] in x and
// [originY − (row+1)·cellHeight, originY − row·cellHeight] in y; its height is the
// value at the cell centre. Units: CRS units, which must be metres (projected CRS);
// heights in metres above the DEM's vertical datum. No-data cells hold NaN.
//
// readElevationGrid resamples a GDAL raster (band 1) bilinearly at the centres of the
// asked grid, which must lie inside the raster; the grid's CRS is the raster's.
// Failures (unreadable file, geographic or rotated raster, grid outside the raster)
// come back as Result errors naming the path and the reason.
#pragma once

#include <string>
#include <vector>

#include "sylva/core/base/Result.h"

namespace sylva {

struct GridGeometry {
    double originX = 0.0;     // west edge, CRS metres
    double originY = 0.0;     // north edge, CRS metres
    double cellWidth = 1.0;   // metres, > 0
    double cellHeight = 1.0;  // metres, > 0 (rows grow southwards)
    int width = 0;
    int height = 0;

    double centreX(double col) const { return originX + (col + 0.5) * cellWidth; }
    double centreY(double row) const { return originY - (row + 0.5) * cellHeight; }
    // Fractional grid coordinates whose integers are cell centres.
    double colOf(double x) const { return (x - originX) / cellWidth - 0.5; }
    double rowOf(double y) const { return (originY - y) / cellHeight - 0.5; }
    // True when (x, y) lies in the hull of the cell centres (where heights interpolate).
    bool containsCentreHull(double x, double y) const;
    // GDAL geotransform (north-up).
    void geoTransform(double out[6]) const;
};

struct ElevationGrid {
    GridGeometry geometry;
    std::vector<float> heights;  // row-major, width × height, metres, NaN = no data
    std::string crsWkt;          // the CRS (WKT), empty when unknown

    float at(int col, int row) const {
        return heights[std::size_t(row) * std::size_t(geometry.width) + std::size_t(col)];
    }
    // Bilinear height at fractional grid coordinates (clamped to the grid).
    double interpolate(double col, double row) const;
};

// The bounds and cell size of a raster file (band 1), for checks before reading.
struct RasterInfo {
    GridGeometry geometry;
    std::string crsWkt;
    bool projected = false;
};
Result<RasterInfo> readRasterInfo(const std::string& path);

Result<ElevationGrid> readElevationGrid(const std::string& path, const GridGeometry& grid);

}  // namespace sylva
