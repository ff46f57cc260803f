// ToneMapping: the CPU copy of the shading pass's display transform and its inverse
// for drawn overlays, checked against the formula sRGB(1 − exp(−x)) written out.
#include "sylva/core/image/ToneMapping.h"

#include <gtest/gtest.h>

#include <cmath>

namespace sylva {
namespace {

TEST(ToneMapping, DisplayFollowsTheShadersCurve) {
    EXPECT_EQ(ToneMapping::display(0.0f), 0);
    EXPECT_EQ(ToneMapping::display(-3.0f), 0);
    EXPECT_EQ(ToneMapping::display(100.0f), 255);
    // x = ln 2: 1 − exp(−x) = 0.5, sRGB(0.5) = 1.055 · 0.5^(1/2.4) − 0.055 = 0.7354 → 188.
    EXPECT_EQ(ToneMapping::display(std::log(2.0f)), 188);
}

TEST(ToneMapping, RadianceIsTheInverseForEveryByte) {
    for (int value = 0; value < 256; ++value) {
        const float radiance = ToneMapping::radiance(static_cast<std::uint8_t>(value));
        EXPECT_TRUE(std::isfinite(radiance));
        EXPECT_EQ(ToneMapping::display(radiance), value) << value;
    }
}

TEST(ToneMapping, WholeImageKeepsAlpha) {
    LinearImage image(2, 1, std::log(2.0f), 0.0f, 100.0f, 0.5f);
    const RgbaImage shown = ToneMapping::display(image);
    EXPECT_EQ(shown.at(1, 0)[0], 188);
    EXPECT_EQ(shown.at(1, 0)[1], 0);
    EXPECT_EQ(shown.at(1, 0)[2], 255);
    EXPECT_EQ(shown.at(1, 0)[3], 128);
}

// The inverse of a whole 8-bit image (PNG inputs of EXR comparisons) displays as it again.
TEST(ToneMapping, WholeImageRadianceDisplaysAsTheImage) {
    RgbaImage image(3, 2, 0, 0, 0, 0);
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
        image.pixels[i] = static_cast<std::uint8_t>(i * 23);
    }
    const LinearImage radiance = ToneMapping::radiance(image);
    ASSERT_EQ(radiance.width, 3);
    ASSERT_EQ(radiance.height, 2);
    EXPECT_FLOAT_EQ(radiance.at(1, 0)[0], ToneMapping::radiance(std::uint8_t(4 * 23)));
    EXPECT_FLOAT_EQ(radiance.at(1, 0)[3], float(7 * 23) / 255.0f);  // alpha stays linear
    EXPECT_EQ(ToneMapping::display(radiance).pixels, image.pixels);
}

}  // namespace
}  // namespace sylva
