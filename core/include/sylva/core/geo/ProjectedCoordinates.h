// ProjectedCoordinates: positions written in a project's coordinate reference system
// (e.g. UTM metres, "EPSG:31985") converted to WGS84 geodetic latitude/longitude
// through GDAL/PROJ. Easting/northing order, metres (or the CRS's linear unit).
#pragma once

#include <string_view>

#include <glm/glm.hpp>

#include "sylva/core/base/Result.h"

namespace sylva {

struct GeodeticPoint {
    double latitude = 0.0;   // radians
    double longitude = 0.0;  // radians
};

class ProjectedCoordinates {
public:
    // Fails with "unknown coordinate reference system 'X'" or "cannot convert ..."
    // (the caller adds the location). Any CRS definition GDAL accepts: "EPSG:n", WKT,
    // PROJ strings. Thread-safe; transformations are cached per thread.
    static Result<GeodeticPoint> toGeodetic(std::string_view crs, double x, double y);
    // The inverse: (x, y) in `crs` units of WGS84 (latitude, longitude) radians.
    static Result<glm::dvec2> fromGeodetic(std::string_view crs, double latitude, double longitude);
    // Checks that `crs` is a known, convertible coordinate reference system.
    static Status validate(std::string_view crs);
};

}  // namespace sylva
