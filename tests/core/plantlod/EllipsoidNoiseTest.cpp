#include "sylva/core/plantlod/EllipsoidNoise.h"

#include <gtest/gtest.h>

#include <random>

namespace sylva {
namespace {

// Values from an independent Python transcription of the formula documented in
// EllipsoidNoise.h (the contract the GPU shader copies): if code and documentation
// drift apart, this fails.
TEST(EllipsoidNoise, MatchesTheDocumentedFormula) {
    struct Case {
        glm::vec3 center, q;
        float level;
        std::uint32_t seed;
        float value;
    };
    const Case cases[] = {
        {{0.0f, 0.0f, 0.0f}, {0.1f, -0.2f, 0.3f}, 0.0f, 0x00000000u, 0.4668494463f},
        {{1.5f, -2.25f, 3.0f}, {0.9f, 0.1f, -0.4f}, 2.0f, 0x3E900000u, 0.2449857593f},
        {{10.0f, 0.5f, 7.75f}, {-0.7f, 0.7f, 0.0f}, 3.0f, 0x11880000u, 0.5776785612f},
        {{0.25f, 0.125f, 2.0f}, {0.0f, -1.0f, 0.0f}, 5.0f, 0x30800000u, 0.4847797751f},
    };
    for (const Case& c : cases) {
        EXPECT_EQ(ellipsoidNoiseSeed(c.center), c.seed);
        EXPECT_EQ(ellipsoidNoise(c.q, c.level, c.seed), c.value);
    }
}

TEST(EllipsoidNoise, IsUniformWhiteNoise) {
    // A threshold t must discard a fraction t of the cells (the calibration relies on it).
    std::mt19937 random(3);
    std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
    int below = 0;
    const int samples = 200000;
    for (int i = 0; i < samples; ++i) {
        const glm::vec3 q(unit(random), unit(random), unit(random));
        below += ellipsoidNoise(q, 6.0f, 12345u) < 0.3f ? 1 : 0;
    }
    EXPECT_NEAR(below / double(samples), 0.3, 0.01);
}

}  // namespace
}  // namespace sylva
