// SolarPosition against published values: the NREL SPA paper's worked example
// (Reda & Andreas 2008, NREL/TP-560-34302, Table A4.1), outputs of the NOAA solar
// calculator, the 2024 equinoxes and solstices (US Naval Observatory times, to the
// minute) and the equation of time's yearly extremes.
#include "sylva/core/geo/SolarPosition.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "sylva/core/scene/DateTime.h"

namespace sylva {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

double instant(const char* text) {
    auto parsed = DateTime::parse(text);
    EXPECT_TRUE(parsed.ok()) << text;
    auto seconds = parsed.value().unixSeconds();
    EXPECT_TRUE(seconds.ok()) << text;
    return seconds.value();
}

TEST(SolarPositionTest, NrelSpaWorkedExample) {
    // 2003-10-17 12:30:30 local standard time (-7 h), Golden, Colorado:
    // topocentric zenith 50.11162°, azimuth 194.34024°.
    const SunDirection sun = SolarPosition::seenFrom(instant("2003-10-17T12:30:30-07:00"),
                                                     39.742476 * kDegree, -105.1786 * kDegree);
    EXPECT_NEAR(90.0 - sun.elevation / kDegree, 50.11162, 0.1);
    EXPECT_NEAR(sun.azimuth / kDegree, 194.34024, 0.1);
}

TEST(SolarPositionTest, NoaaCalculatorHelsinki) {
    // NOAA solar calculator, Helsinki 2022-09-04 10:19:29 UTC (solar noon): apparent
    // elevation 36.96°, azimuth 180.05°, declination 7.11°.
    const double t = instant("2022-09-04T10:19:29Z");
    const SunDirection sun = SolarPosition::seenFrom(t, 60.17 * kDegree, 24.94 * kDegree);
    EXPECT_NEAR(sun.elevation / kDegree, 36.96, 0.1);
    EXPECT_NEAR(sun.azimuth / kDegree, 180.05, 0.1);
    EXPECT_NEAR(SolarPosition::at(t).declination / kDegree, 7.11, 0.02);
}

TEST(SolarPositionTest, EquinoxesAndSolstices2024) {
    // Obliquity of the ecliptic in 2024: 23.4362° (IAU 2006: 23.439279° − 0.013004° T).
    EXPECT_NEAR(SolarPosition::at(instant("2024-03-20T03:06Z")).declination / kDegree, 0.0, 0.01);
    EXPECT_NEAR(SolarPosition::at(instant("2024-06-20T20:51Z")).declination / kDegree, 23.4362,
                0.01);
    EXPECT_NEAR(SolarPosition::at(instant("2024-09-22T12:44Z")).declination / kDegree, 0.0, 0.01);
    EXPECT_NEAR(SolarPosition::at(instant("2024-12-21T09:20Z")).declination / kDegree, -23.4362,
                0.01);
}

TEST(SolarPositionTest, EquationOfTimeExtremes) {
    // About −14 min 14 s around 11 February and +16 min 25 s around 3 November.
    EXPECT_NEAR(SolarPosition::at(instant("2024-02-11T12:00Z")).equationOfTime, -14.23, 0.1);
    EXPECT_NEAR(SolarPosition::at(instant("2024-11-03T12:00Z")).equationOfTime, 16.42, 0.1);
}

TEST(SolarPositionTest, SubsolarPointHasTheSunInTheZenith) {
    for (const char* text : {"2024-06-21T12:00Z", "2024-01-05T03:17Z", "2025-09-30T22:45Z"}) {
        const double t = instant(text);
        const SunPosition sun = SolarPosition::at(t);
        const SunDirection direction =
            SolarPosition::seenFrom(t, sun.subsolarLatitude, sun.subsolarLongitude);
        EXPECT_NEAR(direction.elevationGeometric / kDegree, 90.0, 1e-6) << text;
        EXPECT_GT(sun.subsolarLongitude, -std::numbers::pi - 1e-12);
        EXPECT_LE(sun.subsolarLongitude, std::numbers::pi);
    }
    // Noon UTC, with the equation of time (minutes, 4 min per degree) moving the sun off
    // the prime meridian.
    const SunPosition noon = SolarPosition::at(instant("2024-11-03T12:00Z"));
    EXPECT_NEAR(noon.subsolarLongitude / kDegree, -noon.equationOfTime / 4.0, 1e-9);
}

TEST(SolarPositionTest, AzimuthQuadrants) {
    // Morning sun in the east, evening sun in the west (northern mid-latitude, summer).
    const SunDirection morning = SolarPosition::seenFrom(instant("2024-06-21T07:00:00+02:00"),
                                                         48.0 * kDegree, 11.0 * kDegree);
    const SunDirection evening = SolarPosition::seenFrom(instant("2024-06-21T19:00:00+02:00"),
                                                         48.0 * kDegree, 11.0 * kDegree);
    EXPECT_GT(morning.azimuth / kDegree, 45.0);
    EXPECT_LT(morning.azimuth / kDegree, 110.0);
    EXPECT_GT(evening.azimuth / kDegree, 250.0);
    EXPECT_LT(evening.azimuth / kDegree, 315.0);
}

}  // namespace
}  // namespace sylva
