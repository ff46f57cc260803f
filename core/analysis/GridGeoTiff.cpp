#include "sylva/core/analysis/GridGeoTiff.h"

#include <cpl_string.h>
#include <gdal.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <system_error>
#include <vector>

#include "sylva/core/base/Check.h"
#include "sylva/core/sources/GdalDatasetPool.h"

namespace sylva {

namespace {

std::string gdalReason(const char* fallback) {
    const char* message = CPLGetLastErrorMsg();
    return message != nullptr && *message != '\0' ? message : fallback;
}

Status writeBands(GDALDatasetH ds, const GridGeometry& g, std::span<const GridBand> bands) {
    for (std::size_t b = 0; b < bands.size(); ++b) {
        std::vector<float> band = *bands[b].values;
        SYLVA_CHECK(band.size() == std::size_t(g.width) * std::size_t(g.height));
        GDALRasterBandH h = GDALGetRasterBand(ds, int(b) + 1);
        GDALSetDescription(h, bands[b].name.c_str());
        GDALSetRasterNoDataValue(h, std::numeric_limits<double>::quiet_NaN());
        if (GDALRasterIO(h, GF_Write, 0, 0, g.width, g.height, band.data(), g.width, g.height,
                         GDT_Float32, 0, 0) != CE_None)
            return Error{gdalReason("cannot write a band")};
    }
    std::vector<int> levels;
    for (int f = 2; std::min(g.width, g.height) / f >= 16; f *= 2)
        levels.push_back(f);
    if (!levels.empty() && GDALBuildOverviews(ds, "NEAREST", int(levels.size()), levels.data(), 0,
                                              nullptr, nullptr, nullptr) != CE_None)
        return Error{gdalReason("cannot build overviews")};
    return Status::success();
}

}  // namespace

Status writeGridGeoTiff(const std::filesystem::path& path, const GridGeometry& g,
                        std::span<const GridBand> bands, const std::string& crsWkt) {
    GdalDatasetPool::registerDrivers();
    static std::atomic<int> counter{0};
    const std::filesystem::path temp =
        path.parent_path() / (".sylva-" + std::to_string(getpid()) + "-" +
                              std::to_string(counter++) + "-" + path.filename().string());
    char** options = nullptr;
    options = CSLSetNameValue(options, "COMPRESS", "DEFLATE");
    options = CSLSetNameValue(options, "PREDICTOR", "3");
    options = CSLSetNameValue(options, "TILED", "YES");
    CPLErrorReset();
    CPLPushErrorHandler(CPLQuietErrorHandler);
    GDALDatasetH ds = GDALCreate(GDALGetDriverByName("GTiff"), temp.c_str(), g.width, g.height,
                                 int(bands.size()), GDT_Float32, options);
    CSLDestroy(options);
    Status status = Status::success();
    if (ds == nullptr) {
        status = Error{path.string() + ": " + gdalReason("cannot create the GeoTIFF")};
    } else {
        double gt[6];
        g.geoTransform(gt);
        GDALSetGeoTransform(ds, gt);
        if (!crsWkt.empty())
            GDALSetProjection(ds, crsWkt.c_str());
        status = writeBands(ds, g, bands);
        GDALClose(ds);
        if (status.ok() && CPLGetLastErrorType() >= CE_Failure)
            status = Error{gdalReason("GDAL reported an error")};
        if (!status.ok())
            status = Error{path.string() + ": " + status.error().message};
    }
    CPLPopErrorHandler();
    std::error_code error;
    if (status.ok()) {
        std::filesystem::rename(temp, path, error);
        if (error)
            status = Error{path.string() + ": cannot rename into place: " + error.message()};
    }
    if (!status.ok())
        std::filesystem::remove(temp, error);
    return status;
}

}  // namespace sylva
