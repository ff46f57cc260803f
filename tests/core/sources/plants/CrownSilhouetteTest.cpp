// CrownSilhouette (the far-field canopy's view of the drawn crowns): opaque and outline
// areas of spheres and an ellipsoid against the analytic projections, thinned by the leaf
// fraction as the ray-cast ellipsoids thin them (opacity f (1 − t²)), and the autumn
// colour as vegetation.glsl turns it.
#include "sylva/core/sources/plants/CrownSilhouette.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace sylva {
namespace {

constexpr double kPi = std::numbers::pi;

LodEllipsoid sphere(glm::vec3 centre, float radius, float threshold, glm::vec3 colour) {
    LodEllipsoid e;
    e.center = centre;
    e.radii = glm::vec3(radius);
    e.alphaThreshold = threshold;
    e.color = colour;
    e.weight = 1.0f;
    return e;
}

TEST(CrownSilhouette, SphereAreasByLeafFraction) {
    const double r = 2.0, t = 0.6;
    const std::vector<LodEllipsoid> crown{
        sphere({0.0f, 0.0f, 6.0f}, float(r), float(t), {0.1f, 0.3f, 0.05f})};
    for (const double f : {1.0, 0.5, 0.25, 0.0}) {
        LeafState state;
        state.leafFraction = float(f);
        const CrownSilhouette s = CrownSilhouette::of(crown, state, 0.2, 200);
        const double disc = kPi * r * r;
        const double opaque = disc * f * (1.0 - t * t);
        EXPECT_NEAR(s.topOpaqueArea(), opaque, 0.01 * disc) << f;
        EXPECT_NEAR(s.sideOpaqueArea(), opaque, 0.01 * disc) << f;
        EXPECT_NEAR(s.topOutlineArea(), f > 0.0 ? disc : 0.0, 0.01 * disc) << f;
        EXPECT_NEAR(s.sideOpaqueFraction(), f * (1.0 - t * t), 0.01) << f;
        if (f > 0.0) {
            EXPECT_NEAR(s.albedo().g, 0.3, 1e-6) << f;
        }
    }
    EXPECT_DOUBLE_EQ(CrownSilhouette::ellipsoidOpacity(0.6, 1.0), 1.0 - 0.36);
    EXPECT_DOUBLE_EQ(CrownSilhouette::ellipsoidOpacity(0.0, 2.0), 1.0);
    EXPECT_DOUBLE_EQ(CrownSilhouette::ellipsoidOpacity(0.6, -1.0), 0.0);
}

// Two overlapping spheres: transmission multiplies where their projections overlap. Side
// by side along x, so from above and along y they overlap, along x they are one disc.
TEST(CrownSilhouette, OverlapsMultiplyTransmission) {
    const double r = 1.0, t = 0.5, alpha = 1.0 - t * t;
    const double d = 1.0;  // centre distance
    const std::vector<LodEllipsoid> crown{sphere({-0.5f, 0.0f, 3.0f}, 1.0f, 0.5f, glm::vec3(0.2f)),
                                          sphere({0.5f, 0.0f, 3.0f}, 1.0f, 0.5f, glm::vec3(0.2f))};
    const CrownSilhouette s = CrownSilhouette::of(crown, LeafState{}, 0.2, 400);
    // Lens area of two unit discs at distance d.
    const double lens =
        2.0 * r * r * std::acos(d / (2.0 * r)) - 0.5 * d * std::sqrt(4.0 * r * r - d * d);
    const double disc = kPi * r * r;
    const double top = 2.0 * (disc - lens) * alpha + lens * (1.0 - (1.0 - alpha) * (1.0 - alpha));
    EXPECT_NEAR(s.topOpaqueArea(), top, 0.01 * disc);
    EXPECT_NEAR(s.topOutlineArea(), 2.0 * disc - lens, 0.01 * disc);
}

// An axis-aligned ellipsoid (radii a, b, c) projected along a unit d has the area
// π a b c sqrt(d_x²/a² + d_y²/b² + d_z²/c²).
TEST(CrownSilhouette, EllipsoidProjections) {
    LodEllipsoid e = sphere({0.0f, 0.0f, 5.0f}, 1.0f, 0.0f, glm::vec3(0.2f));
    e.radii = {1.0f, 2.0f, 3.0f};
    const CrownSilhouette s = CrownSilhouette::of({e}, LeafState{}, 0.2, 300);
    const auto area = [](glm::dvec3 d) {
        return kPi * 6.0 * std::sqrt(d.x * d.x + d.y * d.y / 4.0 + d.z * d.z / 9.0);
    };
    EXPECT_NEAR(s.topOpaqueArea(), area({0.0, 0.0, 1.0}), 0.01 * area({0.0, 0.0, 1.0}));
    double side = 0.0;
    for (int k = 0; k < 4; ++k) {
        side += area({std::cos(k * kPi / 4.0), std::sin(k * kPi / 4.0), 0.0}) / 4.0;
    }
    EXPECT_NEAR(s.sideOpaqueArea(), side, 0.01 * side);
    EXPECT_NEAR(s.sideOutlineArea(), side, 0.01 * side);
}

TEST(CrownSilhouette, AutumnColourByLuminance) {
    const glm::vec3 green{0.1f, 0.3f, 0.05f};
    LeafState state;
    state.autumn = 1.0f;
    state.autumnColour = {0.4f, 0.1f, 0.02f};
    const double meanLuminance = 0.25;
    const CrownSilhouette s = CrownSilhouette::of({sphere({0.0f, 0.0f, 4.0f}, 1.0f, 0.3f, green)},
                                                  state, meanLuminance, 64);
    const double luminance = 0.2126 * 0.1 + 0.7152 * 0.3 + 0.0722 * 0.05;
    EXPECT_NEAR(s.albedo().r, 0.4 / meanLuminance * luminance, 1e-5);
    EXPECT_NEAR(s.albedo().b, 0.02 / meanLuminance * luminance, 1e-5);
    EXPECT_EQ(CrownSilhouette::of({}, state, 0.2).sideOpaqueArea(), 0.0);
}

}  // namespace
}  // namespace sylva
