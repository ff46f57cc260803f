// SolarPosition: where the sun is for an instant, by the NOAA solar position algorithm
// (the NOAA Global Monitoring Laboratory's solar calculator, after Meeus, "Astronomical
// Algorithms", 1991, ch. 25: low-accuracy sun with nutation and aberration terms).
// Accurate to about 0.01° in declination and 0.1 min in the equation of time between
// 1800 and 2100 — far below what shading can show; the unit tests check it against the
// published NREL SPA example, NOAA calculator outputs and the equinoxes and solstices.
//
// Input instants are UTC (seconds since 1970-01-01T00:00:00Z, POSIX time, no leap
// seconds; ΔT = TT − UT ≈ 70 s is neglected: 0.0008° of solar longitude).
// Angles are radians.
#pragma once

namespace sylva {

struct SunPosition {
    double declination = 0;     // radians, north positive
    double rightAscension = 0;  // radians
    double equationOfTime = 0;  // minutes, apparent minus mean solar time
    double distance = 0;        // astronomical units
    // The subsolar point: where the sun stands in the zenith (geodetic latitude and
    // longitude, radians, east positive, longitude in (−π, π]).
    double subsolarLatitude = 0;
    double subsolarLongitude = 0;
};

struct SunDirection {
    double elevation = 0;           // radians above the horizon, corrected for mean refraction
    double elevationGeometric = 0;  // without refraction
    double azimuth = 0;             // radians clockwise from north, [0, 2π)
};

class SolarPosition {
public:
    // The sun at `unixSeconds` (UTC).
    static SunPosition at(double unixSeconds);
    // The sun as seen from (latitude, longitude) (radians, east positive) at that instant.
    static SunDirection seenFrom(double unixSeconds, double latitude, double longitude);
    // Julian day (UT) of a POSIX instant.
    static double julianDay(double unixSeconds) { return unixSeconds / 86400.0 + 2440587.5; }
};

}  // namespace sylva
