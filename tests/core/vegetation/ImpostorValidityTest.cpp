// ImpostorValidity (issue 21, seed 000 ch. 7): the precise metric against the analytic
// parallax of a point and its impostor image, the inscribed-angle construction of the
// GVV (Eq. 7.5), and Algorithm 1 keeping an impostor for a camera move just inside the
// bound and regenerating it just outside, counted.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "sylva/core/vegetation/ImpostorValidity.h"

namespace sylva {
namespace {

constexpr double kErrorAngle = 2e-3;  // radians (about two pixels of a 1000-pixel 60° view)

// A group that is a thin column along the view axis: capture from the origin, the box
// from D − R to D + R on the x axis. Its worst corner is the near end (D − R), drawn at
// the box centre (D), so a lateral move y errs by atan(y / (D − R)) − atan(y / D).
struct AxialGroup {
    double distance = 500.0, halfDepth = 40.0;
    ImpostorCapture capture() const {
        ImpostorCapture c;
        c.viewpoint = glm::dvec3(0.0);
        c.boxMinimum = glm::dvec3(distance - halfDepth, 0.0, 0.0);
        c.boxMaximum = glm::dvec3(distance + halfDepth, 0.0, 0.0);
        return c;
    }
    double analyticError(double y) const {
        return std::atan(y / (distance - halfDepth)) - std::atan(y / distance);
    }
    // The lateral move at which the analytic error reaches the threshold (bisection).
    double analyticBound(double errorAngle) const {
        double low = 0.0, high = distance;
        for (int i = 0; i < 200; ++i) {
            const double middle = 0.5 * (low + high);
            (analyticError(middle) < errorAngle ? low : high) = middle;
        }
        return 0.5 * (low + high);
    }
};

TEST(ImpostorValidityTest, PreciseMetricIsTheAnalyticParallax) {
    const AxialGroup group;
    for (double y : {0.5, 3.0, 20.0, 90.0}) {
        EXPECT_NEAR(ImpostorValidity::impostorError(group.capture(), glm::dvec3(0.0, y, 0.0)),
                    group.analyticError(y), 1e-12)
            << y;
    }
    // From the capture viewpoint the impostor is exact.
    EXPECT_NEAR(ImpostorValidity::impostorError(group.capture(), glm::dvec3(0.0)), 0.0, 1e-15);
}

TEST(ImpostorValidityTest, MoveJustInsideTheBoundKeepsJustOutsideRegenerates) {
    const AxialGroup group;
    const double bound = group.analyticBound(kErrorAngle);
    ASSERT_GT(bound, 1.0);
    ImpostorValidity validity(kErrorAngle);
    ImpostorGuard guard;
    validity.recapture(guard, group.capture());
    // The GVV is conservative: it never reaches past the analytic bound.
    EXPECT_GT(guard.volumeRadius, 0.0);
    EXPECT_LE(guard.volumeRadius, bound);

    EXPECT_NE(validity.test(guard, glm::dvec3(0.0, 0.999 * bound, 0.0)),
              ImpostorVerdict::Regenerate);
    EXPECT_EQ(validity.test(guard, glm::dvec3(0.0, 1.001 * bound, 0.0)),
              ImpostorVerdict::Regenerate);
    EXPECT_EQ(validity.counters().tests, 2u);
    EXPECT_EQ(validity.counters().regenerated, 1u);
    EXPECT_EQ(validity.counters().validByMetric, 1u);  // 0.999 bound is outside the GVV
}

TEST(ImpostorValidityTest, GuaranteedVolumeIsTightAlongItsWorstDirection) {
    const AxialGroup group;
    ImpostorValidity validity(kErrorAngle);
    ImpostorGuard guard;
    validity.recapture(guard, group.capture());
    const double radius = guard.volumeRadius;
    const glm::dvec3 inside =
        ImpostorValidity::worstMove(group.capture(), glm::dvec3(0.0), kErrorAngle, 0.999 * radius);
    const glm::dvec3 outside =
        ImpostorValidity::worstMove(group.capture(), glm::dvec3(0.0), kErrorAngle, 1.001 * radius);
    EXPECT_LE(ImpostorValidity::impostorError(group.capture(), inside), kErrorAngle);
    EXPECT_GT(ImpostorValidity::impostorError(group.capture(), outside), kErrorAngle);
    // Inside the GVV the metric is not evaluated.
    EXPECT_EQ(validity.test(guard, inside), ImpostorVerdict::InsideGuaranteedVolume);
    EXPECT_EQ(validity.counters().insideGuaranteedVolume, 1u);
    EXPECT_EQ(validity.counters().validByMetric, 0u);
}

TEST(ImpostorValidityTest, ErrorCircleHasTheInscribedAngle) {
    // Every viewpoint at clearance 0 sees the segment under exactly the error angle
    // (central-angle theorem, r = d / (2 sin ε)).
    const glm::dvec3 p(10.0, 2.0, -3.0), q(14.0, 2.5, -1.0);
    std::mt19937 random(3);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    for (int i = 0; i < 20; ++i) {
        const glm::dvec3 start = glm::dvec3(unit(random), unit(random), unit(random)) * 50.0;
        const double clearance = ImpostorValidity::segmentClearance(p, q, start, 0.05);
        if (clearance <= 0.0) {
            continue;
        }
        // Walk toward the segment's midpoint until the clearance is 0 (bisection).
        const glm::dvec3 middle = 0.5 * (p + q);
        double low = 0.0, high = 1.0;
        for (int k = 0; k < 200; ++k) {
            const double t = 0.5 * (low + high);
            const glm::dvec3 v = start + (middle - start) * t;
            (ImpostorValidity::segmentClearance(p, q, v, 0.05) > 0.0 ? low : high) = t;
        }
        const glm::dvec3 v = start + (middle - start) * low;
        const glm::dvec3 a = glm::normalize(p - v), b = glm::normalize(q - v);
        EXPECT_NEAR(std::acos(glm::dot(a, b)), 0.05, 1e-7);
    }
}

TEST(ImpostorValidityTest, EveryViewpointInsideTheVolumeIsValid) {
    std::mt19937 random(11);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    for (int group = 0; group < 30; ++group) {
        ImpostorCapture capture;
        const glm::dvec3 centre(300.0 + 200.0 * unit(random), 150.0 * unit(random),
                                20.0 * unit(random));
        const glm::dvec3 half(10.0 + 30.0 * std::abs(unit(random)),
                              10.0 + 30.0 * std::abs(unit(random)),
                              5.0 + 10.0 * std::abs(unit(random)));
        capture.boxMinimum = centre - half;
        capture.boxMaximum = centre + half;
        capture.viewpoint = glm::dvec3(unit(random), unit(random), unit(random)) * 5.0;
        const double radius =
            ImpostorValidity::guaranteedValidRadius(capture, capture.viewpoint, kErrorAngle);
        ASSERT_GT(radius, 0.0);
        for (int i = 0; i < 100; ++i) {
            glm::dvec3 direction(unit(random), unit(random), unit(random));
            if (glm::length(direction) < 1e-3) {
                continue;
            }
            const glm::dvec3 v =
                capture.viewpoint + glm::normalize(direction) * radius * std::abs(unit(random));
            EXPECT_LE(ImpostorValidity::impostorError(capture, v), kErrorAngle * (1 + 1e-9));
        }
    }
}

}  // namespace
}  // namespace sylva
