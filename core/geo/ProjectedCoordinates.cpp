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

// From `crs` to WGS84 longitude/latitude, or back (`toProjected`).
const Transformation& transformationFor(std::string_view crs, bool toProjected = false) {
    thread_local std::map<std::string, Transformation, std::less<>> cache;
    const std::string key = (toProjected ? "to " : "from ") + std::string(crs);
    if (auto it = cache.find(key); it != cache.end()) {
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
        result.transform.reset(toProjected ? OGRCreateCoordinateTransformation(&target, &source)
                                           : OGRCreateCoordinateTransformation(&source, &target));
        if (!result.transform) {
            result.error = "cannot convert from '" + text + "' to WGS84";
        }
    }
    return cache.emplace(key, std::move(result)).first->second;
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

Result<glm::dvec2> ProjectedCoordinates::fromGeodetic(std::string_view crs, double latitude,
                                                      double longitude) {
    const Transformation& transformation = transformationFor(crs, true);
    if (!transformation.transform) {
        return Error{transformation.error};
    }
    constexpr double kDegree = std::numbers::pi / 180.0;
    double x = longitude / kDegree, y = latitude / kDegree;
    if (!transformation.transform->Transform(1, &x, &y) || !std::isfinite(x) || !std::isfinite(y)) {
        return Error{"cannot convert (" + std::to_string(latitude / kDegree) + "°, " +
                     std::to_string(longitude / kDegree) + "°) to '" + std::string(crs) + "'"};
    }
    return glm::dvec2(x, y);
}

Status ProjectedCoordinates::validate(std::string_view crs) {
    const Transformation& transformation = transformationFor(crs);
    if (!transformation.transform) {
        return Error{transformation.error};
    }
    return Status::success();
}

}  // namespace sylva
