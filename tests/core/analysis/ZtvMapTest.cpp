// The styled ZTV map: Horn's hillshade against the analytic shading of tilted planes, the
// colour of a cell seen by k targets against the legend's k-th swatch, the distance rings
// at their distance, and the written PNG read back.
#include "sylva/core/analysis/ZtvMap.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <vector>

#include "sylva/core/image/ImageWriter.h"

namespace sylva {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// A grid of `w` × `h` cells of `cell` metres whose height is height(x, y) at the centres.
template <typename F>
ElevationGrid planeGrid(int w, int h, double cell, F height) {
    ElevationGrid grid;
    grid.geometry = {500000.0, 5500000.0, cell, cell, w, h};
    for (int row = 0; row < h; ++row)
        for (int col = 0; col < w; ++col)
            grid.heights.push_back(
                float(height(grid.geometry.centreX(col), grid.geometry.centreY(row))));
    return grid;
}

// Plane of slope angle `slopeDeg` whose downhill direction points to azimuth `aspectDeg`
// (clockwise from north); its analytic Lambert shade under the sun at (az, alt).
ElevationGrid tiltedPlane(double slopeDeg, double aspectDeg) {
    const double g = std::tan(slopeDeg * kDeg);
    const double ex = std::sin(aspectDeg * kDeg), ny = std::cos(aspectDeg * kDeg);
    return planeGrid(9, 9, 10.0, [&](double x, double y) {
        return 100.0 - g * ((x - 500000.0) * ex + (y - 5500000.0) * ny);
    });
}

double analyticShade(double slopeDeg, double aspectDeg, double azDeg, double altDeg) {
    const double zenith = (90.0 - altDeg) * kDeg, slope = slopeDeg * kDeg;
    return std::cos(zenith) * std::cos(slope) +
           std::sin(zenith) * std::sin(slope) * std::cos((azDeg - aspectDeg) * kDeg);
}

TEST(ZtvMap, HillshadeOfTiltedPlanesMatchesHorn) {
    const double slope = 20.0;
    struct Case {
        double aspect;
        double expected;
    };
    // Towards the sun (faces north-west), away (south-east), across (north-east).
    const Case cases[] = {{315.0, std::cos((45.0 - slope) * kDeg)},
                          {135.0, std::cos((45.0 + slope) * kDeg)},
                          {45.0, std::cos(45.0 * kDeg) * std::cos(slope * kDeg)},
                          {270.0, analyticShade(slope, 270.0, 315.0, 45.0)}};
    for (const Case& c : cases) {
        const ElevationGrid grid = tiltedPlane(slope, c.aspect);
        const std::vector<float> shade = hillshade(grid);
        EXPECT_NEAR(c.expected, analyticShade(slope, c.aspect, 315.0, 45.0), 1e-12);
        for (int row = 1; row < 8; ++row)
            for (int col = 1; col < 8; ++col)
                EXPECT_NEAR(shade[std::size_t(row) * 9 + col], c.expected, 2e-5)
                    << "aspect " << c.aspect << " cell " << col << "," << row;
    }
    // Flat ground: sin(altitude); a no-data cell stays NaN.
    ElevationGrid flat = planeGrid(5, 5, 30.0, [](double, double) { return 12.0; });
    flat.heights[12] = std::nanf("");
    const std::vector<float> shade = hillshade(flat);
    EXPECT_NEAR(shade[0], std::sin(45.0 * kDeg), 1e-6);
    EXPECT_TRUE(std::isnan(shade[12]));
}

ViewshedResult emptyResult(const GridGeometry& g) {
    ViewshedResult r;
    r.geometry = g;
    const std::size_t cells = std::size_t(g.width) * g.height;
    r.visible.assign(cells, 0);
    r.count.assign(cells, 0);
    r.fraction.assign(cells, 0.0f);
    return r;
}

std::array<std::uint8_t, 3> rgbAt(const RgbaImage& image, int x, int y) {
    const std::uint8_t* p = image.at(x, y);
    return {p[0], p[1], p[2]};
}

TEST(ZtvMap, CellSeenByKTargetsHasTheKthLegendColour) {
    const ElevationGrid grid = planeGrid(60, 40, 25.0, [](double, double) { return 50.0; });
    const GridGeometry& g = grid.geometry;
    ViewshedResult result = emptyResult(g);
    // Three targets in the top-left corner: the legend goes bottom right.
    const std::vector<ViewshedTarget> targets = {{g.centreX(3), g.centreY(3), 100.0},
                                                 {g.centreX(5), g.centreY(3), 100.0},
                                                 {g.centreX(3), g.centreY(5), 100.0}};
    const std::array<int, 3> cols = {20, 30, 40};
    for (int k = 1; k <= 3; ++k) {
        const std::size_t cell = std::size_t(12) * g.width + std::size_t(cols[std::size_t(k - 1)]);
        result.count[cell] = std::uint16_t(k);
        result.visible[cell] = 1;
    }
    ZtvMapOptions options;
    options.title = "test";
    options.scale = 8;
    const ZtvMap map = drawZtvMap(grid, result, targets, options);
    ASSERT_EQ(map.image.width, 480);
    ASSERT_EQ(map.image.height, 320);
    ASSERT_EQ(map.layout.swatchCentres.size(), 3u);
    EXPECT_GT(map.layout.legendBox[0], map.image.width / 2);  // opposite the targets
    const auto ring = kZtvRingColour;
    for (int k = 1; k <= 3; ++k) {
        const auto [sx, sy] = map.layout.swatchCentres[std::size_t(k - 1)];
        const auto swatch = rgbAt(map.image, sx, sy);
        // Every pixel of the cell that no ring crosses has the swatch's colour.
        int same = 0, other = 0;
        const int x0 = cols[std::size_t(k - 1)] * 8;
        for (int y = 12 * 8; y < 13 * 8; ++y) {
            for (int x = x0; x < x0 + 8; ++x) {
                const auto c = rgbAt(map.image, x, y);
                if (c != ring)
                    ++(c == swatch ? same : other);
            }
        }
        EXPECT_GT(same, 40) << "count " << k;
        EXPECT_EQ(other, 0) << "count " << k;
        // The swatch is the count's colour blended over flat ground, not the bare grey.
        const auto grey = rgbAt(map.image, 10 * 8 + 4, 20 * 8 + 4);
        EXPECT_NE(swatch, grey);
        const auto colour = ztvCountColour(k, 3);
        EXPECT_NEAR(swatch[0], grey[0] * (1 - kZtvAlpha) + colour[0] * kZtvAlpha, 0.51);
        EXPECT_NEAR(swatch[2], grey[2] * (1 - kZtvAlpha) + colour[2] * kZtvAlpha, 0.51);
    }
    EXPECT_NE(ztvCountColour(1, 3), ztvCountColour(2, 3));
    EXPECT_NE(ztvCountColour(2, 3), ztvCountColour(3, 3));
}

TEST(ZtvMap, RingPixelsLieAtTheRingDistance) {
    const ElevationGrid grid = planeGrid(100, 80, 30.0, [](double, double) { return 0.0; });
    const GridGeometry& g = grid.geometry;
    const ViewshedResult result = emptyResult(g);
    const std::vector<ViewshedTarget> targets = {{g.centreX(40), g.centreY(30), 50.0}};
    ZtvMapOptions options;
    options.scale = 4;
    const ZtvMap map = drawZtvMap(grid, result, targets, options);
    const double spacing = map.layout.ringSpacing;
    EXPECT_EQ(spacing, ringSpacing(std::hypot(60.5 * 30.0, 49.5 * 30.0)));
    EXPECT_EQ(spacing, 500.0);
    std::vector<int> perRing(8, 0);
    for (int y = 0; y < map.image.height; ++y) {
        for (int x = 0; x < map.image.width; ++x) {
            if (rgbAt(map.image, x, y) != kZtvRingColour)
                continue;
            const double mx = g.originX + (x + 0.5) / 4.0 * g.cellWidth;
            const double my = g.originY - (y + 0.5) / 4.0 * g.cellHeight;
            const double d = std::hypot(mx - targets[0].x, my - targets[0].y);
            const double m = std::round(d / spacing);
            ASSERT_GE(m, 1.0) << x << "," << y;
            ASSERT_LE(std::abs(d - m * spacing), g.cellWidth) << x << "," << y << ": " << d;
            if (m < 8)
                ++perRing[std::size_t(m)];
        }
    }
    // The 500 m ring lies inside the map: about 2π·500/7.5 px ≈ 420 px of line.
    EXPECT_GT(perRing[1], 300);
    EXPECT_GT(perRing[2], 300);
    EXPECT_EQ(ringSpacing(10000.0), 2000.0);
    EXPECT_EQ(ringSpacing(5000.0), 1000.0);
    EXPECT_EQ(ringSpacing(30000.0), 5000.0);
}

TEST(ZtvMap, NoDataCellsAreHatchedAndThePngReadsBack) {
    ElevationGrid grid = planeGrid(30, 20, 10.0, [](double x, double) { return x * 0.01; });
    const GridGeometry& g = grid.geometry;
    ViewshedResult result = emptyResult(g);
    for (int col = 0; col < 30; ++col) {
        grid.heights[std::size_t(15) * 30 + col] = std::nanf("");
        result.fraction[std::size_t(15) * 30 + col] = std::nanf("");
    }
    const std::vector<ViewshedTarget> targets = {{g.centreX(25), g.centreY(3), 30.0}};
    ZtvMapOptions options;
    options.scale = 4;
    const ZtvMap map = drawZtvMap(grid, result, targets, options);
    // A no-data cell holds the two hatch colours, a valid cell neither.
    int dark = 0, light = 0;
    for (int x = 0; x < 8 * 4; ++x) {
        const auto c = rgbAt(map.image, x, 15 * 4 + 1);
        dark += c == std::array<std::uint8_t, 3>{70, 70, 70};
        light += c == std::array<std::uint8_t, 3>{205, 205, 205};
    }
    EXPECT_GT(dark, 0);
    EXPECT_GT(light, 0);
    const std::filesystem::path path =
        std::filesystem::path(SYLVA_TEST_OUTPUT_DIR) / "ztv-map" / "map.png";
    std::filesystem::remove_all(path.parent_path());
    ASSERT_TRUE(writeZtvMap(path, map).ok());
    int w = 0, h = 0;
    auto pixels = ImageWriter::readRgba8(path, w, h);
    ASSERT_TRUE(pixels.ok());
    EXPECT_EQ(w, 120);
    EXPECT_EQ(h, 80);
    EXPECT_EQ(*pixels, map.image.pixels);
    EXPECT_EQ(std::distance(std::filesystem::directory_iterator(path.parent_path()), {}), 1);
}

}  // namespace
}  // namespace sylva
