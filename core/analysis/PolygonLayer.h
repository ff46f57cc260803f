// PolygonLayer: the polygons of an OGR vector data set (any driver GDAL reads, any CRS),
// reprojected to an analysis grid's CRS, and burnt into the grid. Private to
// core/analysis: ScreeningSurface reads building footprints with a height attribute,
// ShadowStudy its `site`.
//
// Rasterizing follows GDAL's default rule: a cell is inside when its centre lies in the
// polygon (holes excluded). Where polygons overlap, the later one burnt wins.
//
// Failures (Result errors that start with the file's path): a data set that cannot be
// opened, a missing layer or value attribute, a non-numeric value attribute, a feature
// without geometry, a geometry that is not a polygon or multipolygon, a value that is
// not a positive number (named by the feature's FID), a geometry that cannot be
// reprojected, and GDAL failing to rasterize.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

#include "sylva/core/analysis/ElevationGrid.h"
#include "sylva/core/base/Result.h"

namespace sylva {

struct PolygonGeometryDeleter {
    void operator()(void* geometry) const;  // OGR_G_DestroyGeometry
};
using PolygonGeometry = std::unique_ptr<void, PolygonGeometryDeleter>;  // an OGRGeometryH

struct PolygonFeature {
    PolygonGeometry geometry;  // polygon or multipolygon in the grid's CRS; owned
    double value = 1.0;        // the value attribute, or 1 without one
};

struct PolygonLayerRequest {
    std::string path;                 // the data set
    std::string layer;                // layer name; empty: the first layer
    std::string valueAttribute;       // numeric field read as the value (> 0); empty: none
    std::string valueRole = "value";  // what the value is, in errors: "height"
    std::string role = "a polygon";   // what a feature is, in errors: "a building footprint"
};

Result<std::vector<PolygonFeature>> readPolygons(const PolygonLayerRequest& request,
                                                 const std::string& gridWkt);

// Per cell of `grid` (row-major), the value of the polygon holding its centre, else 0.
// `path` names the data set in errors.
Result<std::vector<float>> rasterizePolygons(const std::vector<PolygonFeature>& polygons,
                                             const GridGeometry& grid, const std::string& gridWkt,
                                             const std::string& path);

// The bounding box [west, south, east, north] of the polygons in the grid's CRS;
// {+inf, +inf, -inf, -inf} for none.
std::array<double, 4> polygonBounds(const std::vector<PolygonFeature>& polygons);

}  // namespace sylva
