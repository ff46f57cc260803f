#include "sylva/core/sources/raster/AdjustSource.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "sylva/core/image/ColorSpace.h"
#include "sylva/core/scheduler/TileEvaluator.h"
#include "sylva/core/sources/raster/ConstantSource.h"

namespace sylva {
namespace {

// Direct computation of the documented order on sRGB-encoded values (no hue).
glm::vec3 direct(const glm::vec3& linear, const AdjustParameters& p) {
    glm::dvec3 c;
    for (int i = 0; i < 3; ++i) {
        double v = linearToSrgb(linear[i]);
        v = std::clamp((v - p.black) / (p.white - p.black), 0.0, 1.0);
        v = std::pow(v, 1.0 / p.gamma) + p.brightness;
        c[i] = (v - 0.5) * p.contrast + 0.5;
    }
    const double luma = 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z;
    glm::vec3 out;
    for (int i = 0; i < 3; ++i) {
        out[i] = srgbToLinear(
            static_cast<float>(std::clamp(luma + (c[i] - luma) * p.saturation, 0.0, 1.0)));
    }
    return out;
}

TEST(AdjustSource, IdentityParametersKeepColours) {
    const ConstantSource input("in", glm::vec4(0.02f, 0.3f, 0.9f, 0.5f));
    const AdjustSource adjust("a", &input, AdjustParameters{});
    for (const glm::vec3 c : {glm::vec3(0.0f), glm::vec3(1.0f), glm::vec3(0.02f, 0.3f, 0.9f)}) {
        const glm::vec3 out = adjust.apply(c);
        EXPECT_NEAR(out.x, c.x, 1e-5);
        EXPECT_NEAR(out.y, c.y, 1e-5);
        EXPECT_NEAR(out.z, c.z, 1e-5);
    }
}

TEST(AdjustSource, TilesMatchADirectPerTexelComputation) {
    const glm::vec4 colour(0.05f, 0.2f, 0.6f, 0.75f);
    const ConstantSource input("in", colour);
    AdjustParameters p;
    p.black = 0.1;
    p.white = 0.8;
    p.gamma = 1.4;
    p.brightness = 0.05;
    p.contrast = 1.3;
    p.saturation = 0.6;
    const AdjustSource adjust("a", &input, p);
    TileEvaluator evaluator(TileFormat{8, 2});
    const ImageTile& tile = *evaluator.tile(adjust, TileKey{}).value();
    const glm::vec3 expected = direct(glm::vec3(colour), p);
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(tile.at(3, 4, c), expected[c], 1e-5) << c;
    }
    EXPECT_EQ(tile.at(3, 4, 3), 0.75f);  // alpha passes through
}

TEST(AdjustSource, SaturationZeroIsGreyAndFullHueTurnIsIdentity) {
    const ConstantSource input("in", glm::vec4(0.5f));
    AdjustParameters grey;
    grey.saturation = 0.0;
    const glm::vec3 g = AdjustSource("g", &input, grey).apply({0.6f, 0.2f, 0.05f});
    EXPECT_NEAR(g.x, g.y, 1e-6);
    EXPECT_NEAR(g.y, g.z, 1e-6);
    AdjustParameters turn;
    turn.hue = 2.0 * 3.14159265358979323846;
    const glm::vec3 t = AdjustSource("t", &input, turn).apply({0.6f, 0.2f, 0.05f});
    EXPECT_NEAR(t.x, 0.6f, 1e-4);
    EXPECT_NEAR(t.y, 0.2f, 1e-4);
    EXPECT_NEAR(t.z, 0.05f, 1e-4);
    AdjustParameters third;
    third.hue = 2.0 * 3.14159265358979323846 / 3.0;
    const glm::vec3 r = AdjustSource("r", &input, third).apply({1.0f, 0.0f, 0.0f});
    EXPECT_GT(r.y, r.x);  // red turns towards green
    EXPECT_GT(r.y, r.z);
}

}  // namespace
}  // namespace sylva
