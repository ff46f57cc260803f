#include "sylva/core/sources/GdalDatasetPool.h"

#include <map>
#include <mutex>

#include <cpl_error.h>
#include <gdal.h>
#include <ogr_srs_api.h>

namespace sylva {
namespace {

struct ThreadHandles {
    std::map<std::string, GDALDatasetH> datasets;
    std::map<std::string, OGRCoordinateTransformationH> transforms;
    ~ThreadHandles() {
        for (auto& [wkt, transform] : transforms) {
            OCTDestroyCoordinateTransformation(transform);
        }
        for (auto& [path, dataset] : datasets) {
            GDALClose(dataset);
        }
    }
};

ThreadHandles& handles() {
    thread_local ThreadHandles instance;
    return instance;
}

std::string lastError(const char* fallback) {
    const char* message = CPLGetLastErrorMsg();
    return (message != nullptr && *message != '\0') ? std::string(message) : std::string(fallback);
}

}  // namespace

void GdalDatasetPool::registerDrivers() {
    static std::once_flag once;
    std::call_once(once, [] { GDALAllRegister(); });
}

Result<void*> GdalDatasetPool::dataset(const std::string& path) {
    registerDrivers();
    ThreadHandles& h = handles();
    if (auto it = h.datasets.find(path); it != h.datasets.end()) {
        return static_cast<void*>(it->second);
    }
    CPLPushErrorHandler(CPLQuietErrorHandler);
    CPLErrorReset();
    GDALDatasetH dataset =
        GDALOpenEx(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, nullptr, nullptr, nullptr);
    const std::string reason = lastError("not a raster GDAL can read");
    CPLPopErrorHandler();
    if (dataset == nullptr) {
        return Error{path + ": " + reason};
    }
    h.datasets.emplace(path, dataset);
    return static_cast<void*>(dataset);
}

Result<void*> GdalDatasetPool::fromLonLat(const std::string& wkt) {
    registerDrivers();
    ThreadHandles& h = handles();
    if (auto it = h.transforms.find(wkt); it != h.transforms.end()) {
        return static_cast<void*>(it->second);
    }
    CPLPushErrorHandler(CPLQuietErrorHandler);
    CPLErrorReset();
    OGRSpatialReferenceH wgs84 = OSRNewSpatialReference(nullptr);
    OSRImportFromEPSG(wgs84, 4326);
    OSRSetAxisMappingStrategy(wgs84, OAMS_TRADITIONAL_GIS_ORDER);
    OGRSpatialReferenceH target = OSRNewSpatialReference(nullptr);
    OGRCoordinateTransformationH transform = nullptr;
    std::string reason;
    if (OSRSetFromUserInput(target, wkt.c_str()) != OGRERR_NONE) {
        reason = "unknown coordinate reference system (" + lastError("unparsable WKT") + ")";
    } else {
        OSRSetAxisMappingStrategy(target, OAMS_TRADITIONAL_GIS_ORDER);
        transform = OCTNewCoordinateTransformation(wgs84, target);
        if (transform == nullptr) {
            reason = "no transformation from WGS84 to its coordinate reference system (" +
                     lastError("unknown reason") + ")";
        }
    }
    OSRDestroySpatialReference(target);
    OSRDestroySpatialReference(wgs84);
    CPLPopErrorHandler();
    if (transform == nullptr) {
        return Error{reason};
    }
    h.transforms.emplace(wkt, transform);
    return static_cast<void*>(transform);
}

int GdalDatasetPool::openCount() {
    return static_cast<int>(handles().datasets.size());
}

}  // namespace sylva
