#include "sylva/core/analysis/ScreeningSurface.h"

#include <ogr_srs_api.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numeric>
#include <vector>

#include "PolygonLayer.h"

namespace sylva {

namespace {

// Building heights per cell (0 = none): footprints burnt lowest first, so the tallest wins.
Result<std::vector<float>> rasterizeBuildings(const ScreenLayer& layer,
                                              const ElevationGrid& ground) {
    PolygonLayerRequest request;
    request.path = layer.path;
    request.layer = layer.layer;
    request.valueAttribute = layer.heightAttribute;
    request.valueRole = "height";
    request.role = "a building footprint";
    auto footprints = readPolygons(request, ground.crsWkt);
    if (!footprints)
        return footprints.error();
    std::stable_sort(
        footprints->begin(), footprints->end(),
        [](const PolygonFeature& a, const PolygonFeature& b) { return a.value < b.value; });
    return rasterizePolygons(*footprints, ground.geometry, ground.crsWkt, layer.path);
}

Result<std::vector<float>> readCanopy(const ScreenLayer& layer, const ElevationGrid& ground) {
    auto info = readRasterInfo(layer.path);
    if (!info)
        return info.error();
    OGRSpatialReferenceH a = OSRNewSpatialReference(info->crsWkt.c_str());
    OGRSpatialReferenceH b = OSRNewSpatialReference(ground.crsWkt.c_str());
    const bool same = a != nullptr && b != nullptr && OSRIsSame(a, b) != 0;
    OSRDestroySpatialReference(a);
    OSRDestroySpatialReference(b);
    if (!same)
        return Error{layer.path +
                     ": the canopy height raster must have the DEM's CRS (warp it "
                     "with gdalwarp -t_srs)"};
    auto canopy = readElevationGrid(layer.path, ground.geometry);
    if (!canopy)
        return canopy.error();
    for (float& h : canopy->heights)
        if (!(h > 0.0f))
            h = 0.0f;  // no-data, zero and negative: open ground
    return std::move(canopy->heights);
}

// Crown columns per cell (0 = none): the cells whose centre lies within a crown's radius of
// its stem, and always the stem's own cell (a crown narrower than a cell still screens).
std::vector<float> rasterizeCrowns(const ScreenLayer& layer, const GridGeometry& g) {
    std::vector<float> heights(std::size_t(g.width) * std::size_t(g.height), 0.0f);
    auto raise = [&](int col, int row, double height) {
        if (col < 0 || row < 0 || col >= g.width || row >= g.height)
            return;
        float& cell = heights[std::size_t(row) * std::size_t(g.width) + std::size_t(col)];
        cell = std::max(cell, float(height));
    };
    for (const PlantCrown& crown : layer.crowns) {
        const double col = g.colOf(crown.x), row = g.rowOf(crown.y);
        raise(int(std::lround(col)), int(std::lround(row)), crown.height);
        const double reachCols = crown.radius / g.cellWidth,
                     reachRows = crown.radius / g.cellHeight;
        for (int r = int(std::ceil(row - reachRows)); r <= int(std::floor(row + reachRows)); ++r)
            for (int c = int(std::ceil(col - reachCols)); c <= int(std::floor(col + reachCols));
                 ++c) {
                const double dx = (c - col) * g.cellWidth, dy = (r - row) * g.cellHeight;
                if (dx * dx + dy * dy <= crown.radius * crown.radius)
                    raise(c, r, crown.height);
            }
    }
    return heights;
}

}  // namespace

Result<ScreeningSurface> buildScreeningSurface(const ElevationGrid& ground,
                                               std::span<const ScreenLayer> layers) {
    const std::size_t cells = ground.heights.size();
    std::vector<float> buildings(cells, 0.0f), canopy(cells, 0.0f);
    for (const ScreenLayer& layer : layers) {
        auto heights = layer.kind == ScreenLayer::Kind::Buildings
                           ? rasterizeBuildings(layer, ground)
                       : layer.kind == ScreenLayer::Kind::Canopy
                           ? readCanopy(layer, ground)
                           : Result<std::vector<float>>(rasterizeCrowns(layer, ground.geometry));
        if (!heights)
            return heights.error();
        std::vector<float>& into = layer.kind == ScreenLayer::Kind::Buildings ? buildings : canopy;
        for (std::size_t i = 0; i < cells; ++i)
            into[i] = std::max(into[i], (*heights)[i]);
    }
    ScreeningSurface out;
    out.surface = ground;
    for (std::size_t i = 0; i < cells; ++i) {
        out.buildingCells += buildings[i] > 0.0f ? 1 : 0;
        out.canopyCells += canopy[i] > 0.0f && canopy[i] >= buildings[i] ? 1 : 0;
        out.surface.heights[i] += std::max(buildings[i], canopy[i]);
    }
    return out;
}

}  // namespace sylva
