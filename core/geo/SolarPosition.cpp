#include "sylva/core/geo/SolarPosition.h"

#include <cmath>
#include <numbers>

namespace sylva {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

double wrapDegrees(double degrees) {
    double wrapped = std::fmod(degrees, 360.0);
    return wrapped < 0 ? wrapped + 360.0 : wrapped;
}

// Minutes after 00:00 UTC of the day that contains the instant.
double minutesOfDay(double unixSeconds) {
    double seconds = std::fmod(unixSeconds, 86400.0);
    if (seconds < 0) {
        seconds += 86400.0;
    }
    return seconds / 60.0;
}

}  // namespace

SunPosition SolarPosition::at(double unixSeconds) {
    // Julian centuries since J2000.0. The NOAA calculator's formulas, in degrees.
    const double t = (julianDay(unixSeconds) - 2451545.0) / 36525.0;
    const double meanLongitude = wrapDegrees(280.46646 + t * (36000.76983 + t * 0.0003032));
    const double meanAnomaly = 357.52911 + t * (35999.05029 - 0.0001537 * t);
    const double eccentricity = 0.016708634 - t * (0.000042037 + 0.0000001267 * t);
    const double m = meanAnomaly * kDegree;
    const double equationOfCentre = std::sin(m) * (1.914602 - t * (0.004817 + 0.000014 * t)) +
                                    std::sin(2 * m) * (0.019993 - 0.000101 * t) +
                                    std::sin(3 * m) * 0.000289;
    const double trueLongitude = meanLongitude + equationOfCentre;
    const double trueAnomaly = meanAnomaly + equationOfCentre;
    // Longitude of the Moon's ascending node drives nutation and the aberration term.
    const double omega = (125.04 - 1934.136 * t) * kDegree;
    const double apparentLongitude =
        (trueLongitude - 0.00569 - 0.00478 * std::sin(omega)) * kDegree;
    const double meanObliquity =
        23.0 + (26.0 + (21.448 - t * (46.815 + t * (0.00059 - t * 0.001813))) / 60.0) / 60.0;
    const double obliquity = (meanObliquity + 0.00256 * std::cos(omega)) * kDegree;

    SunPosition sun;
    sun.distance = 1.000001018 * (1 - eccentricity * eccentricity) /
                   (1 + eccentricity * std::cos(trueAnomaly * kDegree));
    sun.rightAscension =
        std::atan2(std::cos(obliquity) * std::sin(apparentLongitude), std::cos(apparentLongitude));
    sun.declination = std::asin(std::sin(obliquity) * std::sin(apparentLongitude));

    const double y = std::pow(std::tan(obliquity / 2), 2);
    const double l0 = meanLongitude * kDegree;
    sun.equationOfTime =
        4.0 / kDegree *
        (y * std::sin(2 * l0) - 2 * eccentricity * std::sin(m) +
         4 * eccentricity * y * std::sin(m) * std::cos(2 * l0) - 0.5 * y * y * std::sin(4 * l0) -
         1.25 * eccentricity * eccentricity * std::sin(2 * m));

    // The sun culminates where apparent solar time is noon: 4 minutes per degree.
    double longitudeDegrees = (720.0 - minutesOfDay(unixSeconds) - sun.equationOfTime) / 4.0;
    longitudeDegrees = std::fmod(longitudeDegrees + 540.0, 360.0);
    if (longitudeDegrees < 0) {
        longitudeDegrees += 360.0;
    }
    sun.subsolarLongitude = (longitudeDegrees - 180.0) * kDegree;
    sun.subsolarLatitude = sun.declination;
    return sun;
}

SunDirection SolarPosition::seenFrom(double unixSeconds, double latitude, double longitude) {
    const SunPosition sun = at(unixSeconds);
    // Hour angle: the observer's longitude east of the subsolar meridian.
    const double hourAngle = longitude - sun.subsolarLongitude;
    const double cosZenith = std::sin(latitude) * std::sin(sun.declination) +
                             std::cos(latitude) * std::cos(sun.declination) * std::cos(hourAngle);
    const double zenith = std::acos(std::fmax(-1.0, std::fmin(1.0, cosZenith)));

    SunDirection direction;
    direction.elevationGeometric = std::numbers::pi / 2 - zenith;
    // Azimuth from north, clockwise, of the direction to the sun in the local frame.
    const double east = -std::cos(sun.declination) * std::sin(hourAngle);
    const double north = std::cos(latitude) * std::sin(sun.declination) -
                         std::sin(latitude) * std::cos(sun.declination) * std::cos(hourAngle);
    double azimuth = std::atan2(east, north);
    if (azimuth < 0) {
        azimuth += 2 * std::numbers::pi;
    }
    direction.azimuth = azimuth;

    // The NOAA calculator's mean atmospheric refraction (degrees → arc seconds tables).
    const double e = direction.elevationGeometric / kDegree;
    double refractionSeconds = 0;
    if (e <= 85.0) {
        const double te = std::tan(e * kDegree);
        if (e > 5.0) {
            refractionSeconds = 58.1 / te - 0.07 / (te * te * te) + 0.000086 / std::pow(te, 5);
        } else if (e > -0.575) {
            refractionSeconds = 1735.0 + e * (-518.2 + e * (103.4 + e * (-12.79 + e * 0.711)));
        } else {
            refractionSeconds = -20.772 / te;
        }
    }
    direction.elevation = direction.elevationGeometric + refractionSeconds / 3600.0 * kDegree;
    return direction;
}

}  // namespace sylva
