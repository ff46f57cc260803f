// Geodesy: geodesics on the WGS84 ellipsoid through GeographicLib (Karney's
// algorithms, accurate to nanometres). Angles in radians, distances in metres.
#pragma once

namespace sylva {

class Geodesy {
public:
    // Length of the shortest path between two points on the ellipsoid.
    static double distance(double latitude1, double longitude1, double latitude2,
                           double longitude2);
    // The point reached from (latitude, longitude) after `distance` metres along the
    // geodesic that starts at `bearing` (clockwise from north).
    static void destination(double latitude, double longitude, double bearing, double distance,
                            double& latitudeOut, double& longitudeOut);
};

}  // namespace sylva
