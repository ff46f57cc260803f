// AtmosphereParameters from a visibility (Koschmieder) and the CPU atmosphere model's
// own Koschmieder contrast, checked against the analytic law exp(-3.912) = 2 %.
#include <gtest/gtest.h>

#include <cmath>

#include "sylva/core/atmosphere/AtmosphereModel.h"
#include "sylva/core/atmosphere/AtmosphereParameters.h"
#include "sylva/core/atmosphere/Exposure.h"

namespace sylva {
namespace {

TEST(AtmosphereParameters, GroundExtinctionIsKoschmiedersConstantOverTheVisibility) {
    for (const double visibility : {1000.0, 10000.0, 30000.0, 150000.0}) {
        Result<AtmosphereParameters> p = AtmosphereParameters::fromVisibility(visibility);
        ASSERT_TRUE(p);
        EXPECT_NEAR(p->groundExtinctionGreen(), 3.912 / visibility, 1e-12);
        EXPECT_NEAR(p->visibility(), visibility, 1e-6 * visibility);
        EXPECT_GT(p->mieExtinction, 0.0);
    }
}

TEST(AtmosphereParameters, RejectsImpossibleVisibilities) {
    EXPECT_FALSE(AtmosphereParameters::fromVisibility(0.0));
    EXPECT_FALSE(AtmosphereParameters::fromVisibility(-5000.0));
    EXPECT_FALSE(AtmosphereParameters::fromVisibility(400000.0));  // clearer than Rayleigh air
    EXPECT_FALSE(AtmosphereParameters::fromVisibility(30000.0, 10.0));
    const Result<AtmosphereParameters> bad = AtmosphereParameters::fromVisibility(-1.0);
    ASSERT_FALSE(bad);
    EXPECT_NE(bad.error().message.find("positive"), std::string::npos);
}

// The oracle itself: a black target at V along a horizontal ray near the ground
// (contrast = transmittance in a uniformly lit atmosphere) is at 2 % within the
// curvature's thinning of the air over V.
TEST(AtmosphereModel, HorizontalTransmittanceOverTheVisibilityIsTwoPercent) {
    const AtmosphereParameters p = AtmosphereParameters::fromVisibility(20000.0).value();
    const AtmosphereModel model(p);
    const glm::dvec3 position(0.0, 0.0, p.bottomRadius + 2.0);
    EXPECT_NEAR(model.transmittance(position, glm::dvec3(0.0, 1.0, 0.0), 20000.0).g, 0.02, 0.002);
}

TEST(Exposure, SunnySixteen) {
    // Full sun on a horizontal surface, ~100000 lux: EV100 about 15 (the sunny-16 rule).
    EXPECT_NEAR(ev100FromIlluminance(100000.0), 15.3, 0.1);
    EXPECT_NEAR(exposureScale(15.0), 1.0 / (1.2 * 32768.0), 1e-12);
    EXPECT_DOUBLE_EQ(luminance(glm::dvec3(1.0)), 1.0);
}

}  // namespace
}  // namespace sylva
