#include "sylva/core/geo/Geodesy.h"

#include <GeographicLib/Geodesic.hpp>

#include <numbers>

namespace sylva {
namespace {
constexpr double kDegree = std::numbers::pi / 180.0;
}  // namespace

double Geodesy::distance(double latitude1, double longitude1, double latitude2, double longitude2) {
    double metres = 0.0;
    GeographicLib::Geodesic::WGS84().Inverse(latitude1 / kDegree, longitude1 / kDegree,
                                             latitude2 / kDegree, longitude2 / kDegree, metres);
    return metres;
}

void Geodesy::destination(double latitude, double longitude, double bearing, double distance,
                          double& latitudeOut, double& longitudeOut) {
    double latitudeDegrees = 0.0, longitudeDegrees = 0.0;
    GeographicLib::Geodesic::WGS84().Direct(latitude / kDegree, longitude / kDegree,
                                            bearing / kDegree, distance, latitudeDegrees,
                                            longitudeDegrees);
    latitudeOut = latitudeDegrees * kDegree;
    longitudeOut = longitudeDegrees * kDegree;
}

}  // namespace sylva
