#include "sylva/core/sources/raster/HypsometricSource.h"

#include <gtest/gtest.h>

#include "sylva/core/sources/raster/NoiseSource.h"

namespace sylva {
namespace {

void expectColor(const glm::vec3& actual, const glm::vec3& expected, float tolerance = 1e-6f) {
    EXPECT_NEAR(actual.x, expected.x, tolerance);
    EXPECT_NEAR(actual.y, expected.y, tolerance);
    EXPECT_NEAR(actual.z, expected.z, tolerance);
}

HypsometricParameters parameters() {
    HypsometricParameters p;
    p.ramp = {{0.0, {1, 0, 0}}, {100.0, {0, 1, 0}}, {1000.0, {0, 0, 1}}};
    p.water = {0.0f, 0.0f, 0.2f};
    p.shallowWater = {0.0f, 0.5f, 0.5f};
    p.waterDepth = 400.0;
    p.rock = {0.3f, 0.3f, 0.3f};
    p.slopeStart = 0.5;
    p.slopeEnd = 0.8;
    return p;
}

TEST(HypsometricSource, WaterBelowSeaLevel) {
    const NoiseSource height("h", NoiseParameters{});
    const HypsometricSource colour("c", &height, nullptr, parameters());
    expectColor(colour.colorAt(-400.0, 0.0), parameters().water);
    expectColor(colour.colorAt(-5000.0, 0.0), parameters().water);
    expectColor(colour.colorAt(-1e-9, 0.0), parameters().shallowWater, 1e-3f);
    // Water is water even where the sea floor is steep.
    expectColor(colour.colorAt(-5000.0, 1.2), parameters().water);
}

TEST(HypsometricSource, RampStopsGiveTheStopColour) {
    const NoiseSource height("h", NoiseParameters{});
    const HypsometricSource colour("c", &height, nullptr, parameters());
    for (const HypsometricStop& stop : parameters().ramp) {
        expectColor(colour.colorAt(stop.height, 0.0), stop.color);
    }
    expectColor(colour.colorAt(50.0, 0.0), {0.5f, 0.5f, 0.0f});
    expectColor(colour.colorAt(5000.0, 0.0), {0, 0, 1});  // above the last stop
}

TEST(HypsometricSource, SteepSlopesAreRock) {
    const NoiseSource height("h", NoiseParameters{});
    const HypsometricSource colour("c", &height, nullptr, parameters());
    expectColor(colour.colorAt(100.0, 0.8), parameters().rock);
    expectColor(colour.colorAt(500.0, 1.3), parameters().rock);
    expectColor(colour.colorAt(100.0, 0.5), {0, 1, 0});  // slope_start: not yet rock
    const glm::vec3 halfway = colour.colorAt(100.0, 0.65);
    expectColor(halfway, 0.5f * (glm::vec3(0, 1, 0) + parameters().rock), 1e-5f);
}

TEST(HypsometricSource, DefaultRampWhenEmpty) {
    const NoiseSource height("h", NoiseParameters{});
    HypsometricParameters p = parameters();
    p.ramp.clear();
    const HypsometricSource colour("c", &height, nullptr, p);
    const std::vector<HypsometricStop> ramp = HypsometricParameters::defaultRamp();
    expectColor(colour.colorAt(ramp.back().height, 0.0), ramp.back().color);
}

}  // namespace
}  // namespace sylva
