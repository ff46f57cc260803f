#include "sylva/core/image/ImageComparison.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "sylva/core/image/BitmapFont.h"
#include "sylva/core/image/ColorDifference.h"
#include "sylva/core/image/ContactSheet.h"
#include "sylva/core/image/ImageWriter.h"
#include "sylva/core/image/ToneMapping.h"

namespace sylva {
namespace {

// Sharma, Wu and Dalal (2005), Table 1: pairs 1, 2, 3, 7, 17, 24 and 25.
TEST(ColorDifferenceTest, PublishedCiede2000Pairs) {
    struct Pair {
        Lab first, second;
        double deltaE;
    };
    const Pair pairs[] = {
        {{50.0, 2.6772, -79.7751}, {50.0, 0.0, -82.7485}, 2.0425},
        {{50.0, 3.1571, -77.2803}, {50.0, 0.0, -82.7485}, 2.8615},
        {{50.0, 2.8361, -74.0200}, {50.0, 0.0, -82.7485}, 3.4412},
        {{50.0, 0.0, 0.0}, {50.0, -1.0, 2.0}, 2.3669},
        {{50.0, 2.5, 0.0}, {73.0, 25.0, -18.0}, 27.1492},
        {{50.0, 2.5, 0.0}, {50.0, 3.1736, 0.5854}, 1.0000},
        {{50.0, 2.5, 0.0}, {50.0, 3.2972, 0.0}, 1.0000},
    };
    for (const Pair& pair : pairs) {
        EXPECT_NEAR(ColorDifference::deltaE2000(pair.first, pair.second), pair.deltaE, 1e-4);
        EXPECT_NEAR(ColorDifference::deltaE2000(pair.second, pair.first), pair.deltaE, 1e-4);
    }
}

TEST(ColorDifferenceTest, SrgbToLab) {
    const Lab white = ColorDifference::labFromSrgb8(255, 255, 255);
    EXPECT_NEAR(white.lightness, 100.0, 0.01);
    EXPECT_NEAR(white.a, 0.0, 0.01);
    EXPECT_NEAR(white.b, 0.0, 0.01);
    const Lab red = ColorDifference::labFromSrgb8(255, 0, 0);  // L 53.24, a 80.09, b 67.20
    EXPECT_NEAR(red.lightness, 53.24, 0.05);
    EXPECT_NEAR(red.a, 80.09, 0.1);
    EXPECT_NEAR(red.b, 67.20, 0.1);
}

TEST(ImageComparisonTest, BlendMixesInLinearLight) {
    const RgbaImage black(4, 3, 0, 0, 0);
    const RgbaImage white(4, 3, 255, 255, 255);
    auto half = ImageComparison::blend(black, white, 0.5);
    ASSERT_TRUE(half.ok());
    EXPECT_EQ(half.value().at(2, 1)[0], 188);  // linear 0.5 in sRGB
    EXPECT_EQ(ImageComparison::blend(black, white, 0.0).value().pixels, black.pixels);
    EXPECT_EQ(ImageComparison::blend(black, white, 1.0).value().pixels, white.pixels);
    EXPECT_EQ(ImageComparison::blend(black, RgbaImage(5, 3), 0.5).error().message,
              "cannot compare images of different sizes (4x3 and 5x3)");
    EXPECT_EQ(ImageComparison::blend(black, white, 1.5).error().message,
              "blend amount must be within [0, 1]");
}

TEST(ImageComparisonTest, SwipeAndSideBySide) {
    const RgbaImage red(100, 20, 255, 0, 0);
    const RgbaImage blue(100, 20, 0, 0, 255);
    auto swiped = ImageComparison::swipe(red, blue, 0.3);
    ASSERT_TRUE(swiped.ok());
    EXPECT_EQ(swiped.value().at(10, 5)[0], 255);
    EXPECT_EQ(swiped.value().at(90, 5)[2], 255);
    EXPECT_EQ(swiped.value().at(30, 5)[0], 240);  // the divider
    auto pair = ImageComparison::sideBySide(red, blue, 4);
    ASSERT_TRUE(pair.ok());
    EXPECT_EQ(pair.value().width, 204);
    EXPECT_EQ(pair.value().at(99, 0)[0], 255);
    EXPECT_EQ(pair.value().at(104, 0)[2], 255);
}

// The float versions are the same templates: what they draw is the radiance that
// displays as the 8-bit drawing, what they copy is copied unchanged.
TEST(ImageComparisonTest, LinearVersionsDrawTheRadianceOfThe8BitDrawing) {
    const LinearImage bright(100, 20, 7.0f, 0.5f, 0.25f);
    const LinearImage dark(100, 20, 0.0f, 0.125f, 2.0f);
    auto pair = ImageComparison::sideBySide(bright, dark, 4);
    ASSERT_TRUE(pair.ok());
    EXPECT_EQ(pair.value().width, 204);
    EXPECT_EQ(pair.value().at(99, 3)[0], 7.0f);
    EXPECT_EQ(pair.value().at(102, 3)[0], ToneMapping::radiance(16));  // gutter
    EXPECT_EQ(pair.value().at(102, 3)[3], 1.0f);
    EXPECT_EQ(pair.value().at(104, 3)[2], 2.0f);
    auto swiped = ImageComparison::swipe(bright, dark, 0.3);
    ASSERT_TRUE(swiped.ok());
    EXPECT_EQ(swiped.value().at(10, 5)[0], 7.0f);
    EXPECT_EQ(swiped.value().at(90, 5)[2], 2.0f);
    EXPECT_EQ(swiped.value().at(30, 5)[1], ToneMapping::radiance(240));  // the divider
    EXPECT_EQ(swiped.value().at(28, 5)[1], ToneMapping::radiance(32));   // its dark edges
    EXPECT_EQ(swiped.value().at(31, 5)[1], ToneMapping::radiance(32));
    auto half = ImageComparison::blend(bright, dark, 0.25);
    ASSERT_TRUE(half.ok());
    EXPECT_FLOAT_EQ(half.value().at(3, 3)[0], 0.75f * 7.0f);
    EXPECT_FLOAT_EQ(half.value().at(3, 3)[2], 0.75f * 0.25f + 0.25f * 2.0f);
    EXPECT_EQ(ImageComparison::swipe(bright, LinearImage(5, 20), 0.5).error().message,
              "cannot compare images of different sizes (100x20 and 5x20)");
}

TEST(ImageComparisonTest, DifferenceIsZeroWhereEqualAndHotWhereNot) {
    RgbaImage a(240, 160, 90, 120, 60);
    RgbaImage b = a;
    for (int y = 20; y < 60; ++y) {
        for (int x = 100; x < 200; ++x) {
            b.at(x, y)[1] = 20;
        }
    }
    auto heat = ImageComparison::difference(a, b, 20.0);
    ASSERT_TRUE(heat.ok());
    std::uint8_t zero[3];
    ImageComparison::heatColor(0.0, zero);
    EXPECT_EQ(heat.value().at(10, 10)[0], zero[0]);
    EXPECT_EQ(heat.value().at(10, 10)[2], zero[2]);
    const std::uint8_t* hot = heat.value().at(150, 40);
    EXPECT_GT(hot[0] + hot[1], 400);  // saturated end of the ramp (ΔE00 > 20)
}

TEST(BitmapFontTest, GlyphsAndDrawing) {
    // 'A': apex row, crossbar on row 3.
    EXPECT_FALSE(BitmapFont::pixel('A', 0, 0));
    EXPECT_TRUE(BitmapFont::pixel('A', 1, 0));
    for (int column = 0; column < 5; ++column) {
        EXPECT_TRUE(BitmapFont::pixel('A', column, 3));
    }
    EXPECT_EQ(BitmapFont::pixel('\x01', 1, 0), BitmapFont::pixel('?', 1, 0));
    RgbaImage image(40, 20, 0, 0, 0);
    const std::uint8_t white[3] = {255, 255, 255};
    BitmapFont::draw(image, 2, 2, "I", 2, white);
    EXPECT_EQ(image.at(2 + 2 * 2, 2)[0], 255);  // column 2 of 'I', scaled
    EXPECT_EQ(image.at(2, 2 + 2 * 3)[0], 0);
    BitmapFont::draw(image, 35, 15, "clipped", 3, white);  // no crash at the border
}

TEST(ContactSheetTest, GridAndAreaAveragedThumbnails) {
    std::vector<ContactSheetEntry> entries;
    for (int i = 0; i < 5; ++i) {
        RgbaImage image(64, 32);
        for (int y = 0; y < 32; ++y) {
            for (int x = 0; x < 64; ++x) {
                const std::uint8_t v =
                    (x + y) % 2 ? 255 : 0;  // checkerboard: averages to linear 0.5
                image.at(x, y)[0] = image.at(x, y)[1] = image.at(x, y)[2] = v;
            }
        }
        entries.push_back({"view " + std::to_string(i), image});
    }
    auto grid = ContactSheet::build(entries, 32, 3);
    ASSERT_TRUE(grid.ok());
    const int labelHeight = BitmapFont::textHeight(1) + 4;
    EXPECT_EQ(grid.value().width, 3 * (32 + 8) + 8);
    EXPECT_EQ(grid.value().height, 2 * (16 + labelHeight + 8) + 8);
    EXPECT_EQ(grid.value().at(8 + 5, 8 + 5)[0], 188);
    EXPECT_EQ(ContactSheet::build({}, 32).error().message,
              "a contact sheet needs at least one image");

    // A montage to look at: blend, swipe, side by side, difference, labels.
    RgbaImage gradient(320, 180);
    RgbaImage other(320, 180);
    for (int y = 0; y < 180; ++y) {
        for (int x = 0; x < 320; ++x) {
            gradient.at(x, y)[0] = static_cast<std::uint8_t>(x * 255 / 319);
            gradient.at(x, y)[1] = static_cast<std::uint8_t>(y * 255 / 179);
            gradient.at(x, y)[2] = 80;
            other.at(x, y)[0] = static_cast<std::uint8_t>(x * 255 / 319);
            other.at(x, y)[1] = static_cast<std::uint8_t>(
                (x - 160) * (x - 160) + (y - 90) * (y - 90) < 3600 ? 30 : y * 255 / 179);
            other.at(x, y)[2] = 80;
        }
    }
    std::vector<ContactSheetEntry> montage = {
        {"blend 50%", ImageComparison::blend(gradient, other, 0.5).value()},
        {"swipe 0.3", ImageComparison::swipe(gradient, other, 0.3).value()},
        {"difference", ImageComparison::difference(gradient, other).value()},
    };
    ImageComparison::label(montage[0].image, "Before");
    ImageComparison::label(montage[0].image, "After", true);
    auto sheet = ContactSheet::build(montage, 320, 3);
    ASSERT_TRUE(sheet.ok());
    const std::filesystem::path out =
        std::filesystem::path(SYLVA_TEST_OUTPUT_DIR) / "comparison_montage.png";
    ASSERT_TRUE(ImageWriter::writeRgba8(out, sheet.value().width, sheet.value().height,
                                        sheet.value().pixels)
                    .ok());
}

}  // namespace
}  // namespace sylva
