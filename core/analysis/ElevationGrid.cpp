#include "sylva/core/analysis/ElevationGrid.h"

#include <gdal.h>
#include <ogr_srs_api.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "sylva/core/sources/GdalDatasetPool.h"

namespace sylva {

namespace {

struct DatasetCloser {
    void operator()(void* dataset) const { GDALClose(static_cast<GDALDatasetH>(dataset)); }
};
using DatasetPtr = std::unique_ptr<void, DatasetCloser>;

std::string lastGdalError(const char* fallback) {
    const char* message = CPLGetLastErrorMsg();
    return message != nullptr && *message != '\0' ? message : fallback;
}

Result<DatasetPtr> openRaster(const std::string& path) {
    GdalDatasetPool::registerDrivers();
    CPLErrorReset();
    CPLPushErrorHandler(CPLQuietErrorHandler);
    DatasetPtr dataset(GDALOpen(path.c_str(), GA_ReadOnly));
    CPLPopErrorHandler();
    if (!dataset)
        return Error{path + ": " + lastGdalError("cannot open the raster")};
    if (GDALGetRasterCount(static_cast<GDALDatasetH>(dataset.get())) < 1)
        return Error{path + ": the raster has no band"};
    return dataset;
}

}  // namespace

bool GridGeometry::containsCentreHull(double x, double y) const {
    const double col = colOf(x), row = rowOf(y);
    const double eps = 1e-9;
    return col >= -eps && row >= -eps && col <= width - 1 + eps && row <= height - 1 + eps;
}

void GridGeometry::geoTransform(double out[6]) const {
    out[0] = originX;
    out[1] = cellWidth;
    out[2] = 0.0;
    out[3] = originY;
    out[4] = 0.0;
    out[5] = -cellHeight;
}

double ElevationGrid::interpolate(double col, double row) const {
    const int w = geometry.width, h = geometry.height;
    col = std::clamp(col, 0.0, double(w - 1));
    row = std::clamp(row, 0.0, double(h - 1));
    const int c0 = std::min(int(col), std::max(w - 2, 0));
    const int r0 = std::min(int(row), std::max(h - 2, 0));
    const int c1 = std::min(c0 + 1, w - 1), r1 = std::min(r0 + 1, h - 1);
    const double fc = col - c0, fr = row - r0;
    const double top = at(c0, r0) * (1.0 - fc) + at(c1, r0) * fc;
    const double bottom = at(c0, r1) * (1.0 - fc) + at(c1, r1) * fc;
    return top * (1.0 - fr) + bottom * fr;
}

Result<RasterInfo> readRasterInfo(const std::string& path) {
    auto dataset = openRaster(path);
    if (!dataset)
        return dataset.error();
    auto* handle = static_cast<GDALDatasetH>(dataset->get());
    double gt[6];
    if (GDALGetGeoTransform(handle, gt) != CE_None)
        return Error{path + ": the raster has no georeferencing (geotransform)"};
    if (gt[2] != 0.0 || gt[4] != 0.0 || gt[1] <= 0.0 || gt[5] >= 0.0)
        return Error{path + ": the raster is rotated or not north-up"};
    RasterInfo info;
    info.geometry = {
        gt[0], gt[3], gt[1], -gt[5], GDALGetRasterXSize(handle), GDALGetRasterYSize(handle)};
    const char* wkt = GDALGetProjectionRef(handle);
    info.crsWkt = wkt != nullptr ? wkt : "";
    if (!info.crsWkt.empty()) {
        OGRSpatialReferenceH srs = OSRNewSpatialReference(info.crsWkt.c_str());
        info.projected = srs != nullptr && OSRIsProjected(srs) != 0;
        if (srs != nullptr)
            OSRDestroySpatialReference(srs);
    }
    return info;
}

Result<ElevationGrid> readElevationGrid(const std::string& path, const GridGeometry& grid) {
    auto info = readRasterInfo(path);
    if (!info)
        return info.error();
    if (!info->projected)
        return Error{path + ": the elevation raster needs a projected CRS in metres"};
    const GridGeometry& dem = info->geometry;
    const double tolerance = 1e-6 * std::max(dem.cellWidth, dem.cellHeight);
    const double east = grid.originX + grid.width * grid.cellWidth;
    const double south = grid.originY - grid.height * grid.cellHeight;
    if (grid.originX < dem.originX - tolerance || grid.originY > dem.originY + tolerance ||
        east > dem.originX + dem.width * dem.cellWidth + tolerance ||
        south < dem.originY - dem.height * dem.cellHeight - tolerance)
        return Error{path + ": the analysis extent reaches outside the raster"};

    // The window of raster pixels the grid's centres interpolate from (+1 pixel margin).
    const int c0 = std::max(0, int(std::floor(dem.colOf(grid.centreX(0)))) - 1);
    const int r0 = std::max(0, int(std::floor(dem.rowOf(grid.centreY(0)))) - 1);
    const int c1 =
        std::min(dem.width - 1, int(std::ceil(dem.colOf(grid.centreX(grid.width - 1)))) + 1);
    const int r1 =
        std::min(dem.height - 1, int(std::ceil(dem.rowOf(grid.centreY(grid.height - 1)))) + 1);
    ElevationGrid window;
    window.geometry = {dem.originX + c0 * dem.cellWidth,
                       dem.originY - r0 * dem.cellHeight,
                       dem.cellWidth,
                       dem.cellHeight,
                       c1 - c0 + 1,
                       r1 - r0 + 1};
    window.heights.resize(std::size_t(window.geometry.width) * std::size_t(window.geometry.height));
    auto dataset = openRaster(path);
    if (!dataset)
        return dataset.error();
    GDALRasterBandH band = GDALGetRasterBand(static_cast<GDALDatasetH>(dataset->get()), 1);
    CPLPushErrorHandler(CPLQuietErrorHandler);
    const CPLErr read = GDALRasterIO(
        band, GF_Read, c0, r0, window.geometry.width, window.geometry.height, window.heights.data(),
        window.geometry.width, window.geometry.height, GDT_Float32, 0, 0);
    CPLPopErrorHandler();
    if (read != CE_None)
        return Error{path + ": " + lastGdalError("cannot read the raster")};
    int hasNodata = 0;
    const double nodata = GDALGetRasterNoDataValue(band, &hasNodata);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    if (hasNodata != 0)
        for (float& z : window.heights)
            if (z == float(nodata))
                z = nan;

    ElevationGrid out;
    out.geometry = grid;
    out.crsWkt = info->crsWkt;
    out.heights.resize(std::size_t(grid.width) * std::size_t(grid.height));
    for (int row = 0; row < grid.height; ++row)
        for (int col = 0; col < grid.width; ++col)
            out.heights[std::size_t(row) * std::size_t(grid.width) + std::size_t(col)] =
                float(window.interpolate(window.geometry.colOf(grid.centreX(col)),
                                         window.geometry.rowOf(grid.centreY(row))));
    return out;
}

}  // namespace sylva
