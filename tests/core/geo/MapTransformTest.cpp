#include "sylva/core/geo/MapTransform.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

namespace sylva {
namespace {

constexpr double kPi = std::numbers::pi;

// The direct formulas: rotate the hemisphere point into ECEF and convert back with
// asin/atan2, in long double (seed 001 eqs. 5.2-5.4, written with a bearing).
MapOffset<long double> direct(long double lat1, long double lon1, long double theta,
                              long double bearing) {
    const long double s1 = std::sin(lat1), c1 = std::cos(lat1);
    const long double sl = std::sin(lon1), cl = std::cos(lon1);
    const long double up[3] = {c1 * cl, c1 * sl, s1};
    const long double north[3] = {-s1 * cl, -s1 * sl, c1};
    const long double east[3] = {-sl, cl, 0};
    long double d[3];
    for (int i = 0; i < 3; ++i) {
        d[i] = std::cos(theta) * up[i] +
               std::sin(theta) * (std::cos(bearing) * north[i] + std::sin(bearing) * east[i]);
    }
    const long double lat2 = std::atan2(d[2], std::hypot(d[0], d[1]));
    const long double lon2 = std::atan2(d[1], d[0]);
    return {lat2 - lat1, std::remainder(lon2 - lon1, 2 * std::numbers::pi_v<long double>)};
}

TEST(MapTransform, MatchesDirectFormulasAtRandomPointsPolesAndAntimeridian) {
    std::mt19937 random(3);
    std::uniform_real_distribution<double> latitude(-kPi / 2, kPi / 2), longitude(-kPi, kPi),
        bearing(0, 2 * kPi), logTheta(std::log(1e-4), std::log(kPi / 2));
    std::vector<std::pair<double, double>> viewers = {
        {kPi / 2 - 1e-9, 0.3}, {-kPi / 2 + 1e-9, -2.0}, {0.0, kPi - 1e-9},
        {0.5, -kPi + 1e-9},    {kPi / 2 - 0.01, 3.0},   {0.0, 0.0}};
    for (int i = 0; i < 200; ++i) {
        viewers.emplace_back(latitude(random), longitude(random));
    }
    for (const auto& [lat1, lon1] : viewers) {
        const MapTransform<double> transform(lat1);
        for (int j = 0; j < 50; ++j) {
            const double theta = std::exp(logTheta(random));
            const double b = bearing(random);
            const MapOffset<double> ours = transform.offset(theta, std::sin(b), std::cos(b));
            const MapOffset<long double> reference = direct(lat1, lon1, theta, b);
            EXPECT_NEAR(ours.latitude, double(reference.latitude), 1e-12 + 1e-10 * theta);
            // Longitude is undefined at the poles themselves; compare away from them.
            if (std::abs(lat1 + ours.latitude) < kPi / 2 - 1e-6) {
                EXPECT_NEAR(std::remainder(ours.longitude - double(reference.longitude), 2 * kPi),
                            0.0, 1e-9)
                    << lat1 << " " << theta << " " << b;
            }
        }
    }
}

TEST(MapTransform, FloatKeepsRelativePrecisionAtWalkingScale) {
    // 1.7 m eye height: the finest rings span centimetres to metres. The float
    // transform (what the GPU runs) must agree with double to a small fraction of
    // the offset, anywhere on the globe.
    for (double lat1 : {0.0, 0.7, -1.2, kPi / 2 - 1e-4, -kPi / 2 + 1e-3}) {
        const MapTransform<double> precise(lat1);
        const MapTransform<float> single(float(std::sin(lat1)), float(std::cos(lat1)), float(lat1));
        for (double metres : {0.02, 0.5, 3.0, 40.0, 900.0}) {
            const double theta = metres / Ellipsoid::kSemiMajorAxis;
            for (double b : {0.0, 0.9, 2.5, 4.0}) {
                const MapOffset<double> d = precise.offset(theta, std::sin(b), std::cos(b));
                const MapOffset<float> f =
                    single.offset(float(theta), float(std::sin(b)), float(std::cos(b)));
                const glm::dvec3 pd = precise.ecefOffset(d, 1.7);
                const glm::vec3 pf = single.ecefOffset(f, 1.7f);
                const double error = glm::length(glm::dvec3(pf) - pd);
                EXPECT_LT(error, 1e-5 * (metres + 1.7)) << lat1 << " " << metres << " " << b;
            }
        }
    }
}

TEST(MapTransform, EcefOffsetMatchesDifferenceOfEcefPositions) {
    std::mt19937 random(5);
    std::uniform_real_distribution<double> latitude(-1.5, 1.5), longitude(-kPi, kPi),
        delta(-0.3, 0.3), height(-400, 9000);
    for (int i = 0; i < 2000; ++i) {
        const double lat1 = latitude(random), lon1 = longitude(random);
        MapOffset<double> offset{delta(random), delta(random)};
        if (std::abs(lat1 + offset.latitude) > kPi / 2) {
            continue;
        }
        const double h = height(random);
        const glm::dvec3 ours = MapTransform<double>(lat1).ecefOffset(offset, h);
        const glm::dvec3 p2 =
            Ellipsoid::toEcef({lat1 + offset.latitude, lon1 + offset.longitude, h});
        const glm::dvec3 p1 = Ellipsoid::toEcef({lat1, lon1, 0});
        // Rotate the ECEF difference by -lon1 about z into the viewer's meridian frame.
        const glm::dvec3 d = p2 - p1;
        const glm::dvec3 expected(d.x * std::cos(lon1) + d.y * std::sin(lon1),
                                  -d.x * std::sin(lon1) + d.y * std::cos(lon1), d.z);
        EXPECT_NEAR(glm::length(ours - expected), 0.0, 1e-6);
    }
}

TEST(MapTransform, BeyondThePoleTheLongitudeFlipsByPi) {
    // Looking north from 89.9 deg: 0.2 deg further lies on the opposite meridian.
    const double lat1 = kPi / 2 - 0.1 * kPi / 180;
    const MapOffset<double> o = MapTransform<double>(lat1).offset(0.2 * kPi / 180, 0.0, 1.0);
    EXPECT_NEAR(std::abs(o.longitude), kPi, 1e-12);
    EXPECT_NEAR(lat1 + o.latitude, kPi / 2 - 0.1 * kPi / 180, 1e-12);
}

}  // namespace
}  // namespace sylva
