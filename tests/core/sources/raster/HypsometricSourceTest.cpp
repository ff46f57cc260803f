#include "sylva/core/sources/raster/HypsometricSource.h"

#include <gtest/gtest.h>

#include <utility>
#include <vector>

#include "sylva/core/base/Hash.h"
#include "sylva/core/scheduler/TileEvaluator.h"
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

// The brute-force mean of colorAt over [low, high] (an independent oracle for meanColor).
glm::vec3 bruteMean(const HypsometricSource& colour, double low, double high, double slope) {
    constexpr int kSamples = 200000;
    glm::dvec3 sum(0.0);
    for (int i = 0; i < kSamples; ++i) {
        sum += glm::dvec3(colour.colorAt(low + (high - low) * (i + 0.5) / kSamples, slope));
    }
    return glm::vec3(sum / double(kSamples));
}

TEST(HypsometricSource, MeanColourIsTheAverageOverTheHeightRange) {
    const NoiseSource height("h", NoiseParameters{});
    const HypsometricSource colour("c", &height, nullptr, parameters());
    // Across sea level, stops, the water depth, inside one linear piece, and empty.
    for (const auto& [low, high] : std::vector<std::pair<double, double>>{{-50.0, 150.0},
                                                                          {-700.0, 30.0},
                                                                          {20.0, 1500.0},
                                                                          {10.0, 60.0},
                                                                          {-300.0, -10.0},
                                                                          {500.0, 500.0}}) {
        expectColor(colour.meanColor(low, high, 0.2), bruteMean(colour, low, high, 0.2), 2e-4f);
    }
}

// Issue 16: a coarse texel whose centre lies in a thin band is not wholly that band's
// colour. A height ramp rising 200 m per texel eastwards: the tile's colours are the
// area means of the ramp over each texel (brute force over the texel's true heights).
class RampElevation final : public Source {
public:
    RampElevation() : Source("ramp", "test", PortType::Elevation, 1) {
        setParameterHash(ContentHash().add(std::string_view("ramp-v1")).value());
    }
    // Metres at a column position (texel edges at whole numbers): sea level at column 32.
    static double heightAt(double column) { return 200.0 * (column - 32.0); }
    Result<TilePointer> produce(const TileKey& key, TileProvider& provider) const override {
        const TileFormat& format = provider.format();
        auto tile = std::make_shared<ImageTile>(key, format.size, format.border, 1);
        for (int iy = -format.border; iy < format.size + format.border; ++iy) {
            for (int ix = -format.border; ix < format.size + format.border; ++ix) {
                tile->at(ix, iy, 0) = float(heightAt(ix + 0.5));
            }
        }
        return TilePointer(tile);
    }
};

TEST(HypsometricSource, TexelsAreAreaMeansOfTheRamp) {
    const RampElevation ramp;
    HypsometricParameters p = parameters();
    p.slopeStart = p.slopeEnd = 10.0;  // no rock: colour by height alone
    const HypsometricSource colour("c", &ramp, nullptr, p);
    TileEvaluator evaluator(TileFormat{64, 2});
    TileKey key;
    key.level = 6;
    key.x = 70;
    key.y = 20;
    Result<TilePointer> tile = evaluator.tile(colour, key);
    ASSERT_TRUE(tile) << tile.error().message;
    for (int ix = 0; ix < 64; ++ix) {
        const glm::vec3 expected =
            bruteMean(colour, RampElevation::heightAt(ix), RampElevation::heightAt(ix + 1), 0.0);
        const glm::vec3 actual(tile.value()->at(ix, 10, 0), tile.value()->at(ix, 10, 1),
                               tile.value()->at(ix, 10, 2));
        expectColor(actual, expected, 2e-3f);
    }
}

}  // namespace
}  // namespace sylva
