#include "sylva/core/geo/ProjectedCoordinates.h"

#include <ogr_spatialref.h>

#include <cmath>
#include <map>
#include <memory>
#include <numbers>
#include <string>

namespace sylva {
namespace {

struct Transformation {
    std::unique_ptr<OGRCoordinateTransformation> transform;
    std::string error;
};

const Transformation& transformationFor(std::string_view crs) {
    thread_local std::map<std::string, Transformation, std::less<>> cache;
    if (auto it = cache.find(crs); it != cache.end()) {
        return it->second;
    }
    Transformation result;
    OGRSpatialReference source;
    OGRSpatialReference target;
    source.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);  // x = easting
    target.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);  // x = longitude
    const std::string text(crs);
    if (source.SetFromUserInput(text.c_str()) != OGRERR_NONE) {
        result.error = "unknown coordinate reference system '" + text + "'";
    } else if (target.importFromEPSG(4326) != OGRERR_NONE) {
        result.error = "cannot set up WGS84 (EPSG:4326): is the PROJ database installed?";
    } else {
        result.transform.reset(OGRCreateCoordinateTransformation(&source, &target));
        if (!result.transform) {
            result.error = "cannot convert from '" + text + "' to WGS84";
        }
    }
    return cache.emplace(text, std::move(result)).first->second;
}

}  // namespace

Result<GeodeticPoint> ProjectedCoordinates::toGeodetic(std::string_view crs, double x, double y) {
    const Transformation& transformation = transformationFor(crs);
    if (!transformation.transform) {
        return Error{transformation.error};
    }
    double longitude = x, latitude = y;
    if (!transformation.transform->Transform(1, &longitude, &latitude) ||
        !std::isfinite(latitude) || !std::isfinite(longitude)) {
        return Error{"cannot convert (" + std::to_string(x) + ", " + std::to_string(y) +
                     ") from '" + std::string(crs) + "' to WGS84"};
    }
    constexpr double kDegree = std::numbers::pi / 180.0;
    return GeodeticPoint{latitude * kDegree, longitude * kDegree};
}

Status ProjectedCoordinates::validate(std::string_view crs) {
    const Transformation& transformation = transformationFor(crs);
    if (!transformation.transform) {
        return Error{transformation.error};
    }
    return Status::success();
}

}  // namespace sylva
