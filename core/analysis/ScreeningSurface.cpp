#include "sylva/core/analysis/ScreeningSurface.h"

#include <gdal.h>
#include <gdal_alg.h>
#include <ogr_api.h>
#include <ogr_srs_api.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <numeric>
#include <vector>

#include "sylva/core/sources/GdalDatasetPool.h"

namespace sylva {

namespace {

std::string gdalMessage(const char* fallback) {
    const char* message = CPLGetLastErrorMsg();
    return message != nullptr && *message != '\0' ? message : fallback;
}

struct DatasetCloser {
    void operator()(void* dataset) const { GDALClose(static_cast<GDALDatasetH>(dataset)); }
};
using DatasetHandle = std::unique_ptr<void, DatasetCloser>;

struct GeometryDeleter {
    void operator()(void* geometry) const {
        OGR_G_DestroyGeometry(static_cast<OGRGeometryH>(geometry));
    }
};
using GeometryHandle = std::unique_ptr<void, GeometryDeleter>;

struct Footprint {
    GeometryHandle geometry;  // in the grid's CRS
    double height = 0.0;
};

bool numericField(OGRFieldType type) {
    return type == OFTReal || type == OFTInteger || type == OFTInteger64;
}

// The layer's polygons with their heights, reprojected to the grid's CRS.
Result<std::vector<Footprint>> readFootprints(const ScreenLayer& layer,
                                              const std::string& gridWkt) {
    GdalDatasetPool::registerDrivers();  // a process may reach here before any other GDAL use
    CPLErrorReset();
    DatasetHandle dataset(GDALOpenEx(layer.path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY, nullptr,
                                     nullptr, nullptr));
    if (!dataset)
        return Error{layer.path + ": " + gdalMessage("cannot open the vector data set")};
    auto* handle = static_cast<GDALDatasetH>(dataset.get());
    OGRLayerH ogrLayer = layer.layer.empty()
                             ? GDALDatasetGetLayer(handle, 0)
                             : GDALDatasetGetLayerByName(handle, layer.layer.c_str());
    if (ogrLayer == nullptr)
        return Error{layer.path + ": no layer '" + layer.layer + "'"};
    OGRFeatureDefnH definition = OGR_L_GetLayerDefn(ogrLayer);
    const int field = OGR_FD_GetFieldIndex(definition, layer.heightAttribute.c_str());
    if (field < 0)
        return Error{layer.path + ": no height attribute '" + layer.heightAttribute + "'"};
    if (!numericField(OGR_Fld_GetType(OGR_FD_GetFieldDefn(definition, field))))
        return Error{layer.path + ": the height attribute '" + layer.heightAttribute +
                     "' is not numeric"};
    OGRSpatialReferenceH target = OSRNewSpatialReference(gridWkt.c_str());
    OSRSetAxisMappingStrategy(target, OAMS_TRADITIONAL_GIS_ORDER);
    std::vector<Footprint> footprints;
    std::string failure;
    OGR_L_ResetReading(ogrLayer);
    for (OGRFeatureH feature; failure.empty() && (feature = OGR_L_GetNextFeature(ogrLayer));) {
        const std::string name = layer.path + ": feature " + std::to_string(OGR_F_GetFID(feature));
        const double height = OGR_F_GetFieldAsDouble(feature, field);
        OGRGeometryH geometry = OGR_F_GetGeometryRef(feature);
        if (!OGR_F_IsFieldSetAndNotNull(feature, field) || !(height > 0.0) ||
            !std::isfinite(height))
            failure =
                name + ": the height '" + layer.heightAttribute + "' must be a positive number";
        else if (geometry == nullptr || OGR_G_IsEmpty(geometry))
            failure = name + ": no geometry";
        else if (OGR_GT_Flatten(OGR_G_GetGeometryType(geometry)) != wkbPolygon &&
                 OGR_GT_Flatten(OGR_G_GetGeometryType(geometry)) != wkbMultiPolygon)
            failure = name + ": a building footprint must be a polygon";
        if (failure.empty()) {
            GeometryHandle copy(OGR_G_Clone(geometry));
            if (OGR_G_GetSpatialReference(geometry) != nullptr &&
                OGR_G_TransformTo(static_cast<OGRGeometryH>(copy.get()), target) != OGRERR_NONE)
                failure = name + ": cannot reproject the footprint to the DEM's CRS";
            else
                footprints.push_back({std::move(copy), height});
        }
        OGR_F_Destroy(feature);
    }
    OSRDestroySpatialReference(target);
    if (!failure.empty())
        return Error{failure};
    return footprints;
}

// Building heights per cell (0 = none): footprints burnt lowest first, so the tallest wins.
Result<std::vector<float>> rasterizeBuildings(const ScreenLayer& layer,
                                              const ElevationGrid& ground) {
    auto footprints = readFootprints(layer, ground.crsWkt);
    if (!footprints)
        return footprints.error();
    std::sort(footprints->begin(), footprints->end(),
              [](const Footprint& a, const Footprint& b) { return a.height < b.height; });
    const GridGeometry& g = ground.geometry;
    DatasetHandle memory(
        GDALCreate(GDALGetDriverByName("MEM"), "", g.width, g.height, 1, GDT_Float32, nullptr));
    if (!memory)
        return Error{layer.path + ": " +
                     gdalMessage("cannot create the raster for the footprints")};
    auto* handle = static_cast<GDALDatasetH>(memory.get());
    double gt[6];
    g.geoTransform(gt);
    GDALSetGeoTransform(handle, gt);
    GDALSetProjection(handle, ground.crsWkt.c_str());
    std::vector<OGRGeometryH> geometries;
    std::vector<double> heights;
    for (const Footprint& f : *footprints) {
        geometries.push_back(static_cast<OGRGeometryH>(f.geometry.get()));
        heights.push_back(f.height);
    }
    int band = 1;
    if (!geometries.empty() &&
        GDALRasterizeGeometries(handle, 1, &band, int(geometries.size()), geometries.data(),
                                nullptr, nullptr, heights.data(), nullptr, nullptr,
                                nullptr) != CE_None)
        return Error{layer.path + ": " + gdalMessage("cannot rasterize the footprints")};
    std::vector<float> burnt(std::size_t(g.width) * std::size_t(g.height), 0.0f);
    if (GDALRasterIO(GDALGetRasterBand(handle, 1), GF_Read, 0, 0, g.width, g.height, burnt.data(),
                     g.width, g.height, GDT_Float32, 0, 0) != CE_None)
        return Error{layer.path + ": " + gdalMessage("cannot read the rasterized footprints")};
    return burnt;
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
