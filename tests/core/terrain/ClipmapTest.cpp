#include "sylva/core/terrain/Clipmap.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <random>

namespace sylva {
namespace {

constexpr double kPi = std::numbers::pi;

// A tile whose texels encode their own global coordinate, so a texel in the wrong
// place is detected. Counts fetches.
class CoordinateTiles {
public:
    explicit CoordinateTiles(int size) : size_(size) {}
    Result<TilePointer> operator()(const TileKey& key) {
        EXPECT_TRUE(key.valid()) << key.toString();
        ++fetches;
        auto tile = std::make_shared<ImageTile>(key, size_, 1, 2);
        for (int iy = -1; iy <= size_; ++iy) {
            for (int ix = -1; ix <= size_; ++ix) {
                tile->at(ix, iy, 0) = float(key.x * size_ + ix + 1000 * key.lonReduction);
                tile->at(ix, iy, 1) = float(key.y * size_ + iy + 100000 * key.level);
            }
        }
        return TilePointer(tile);
    }
    int fetches = 0;

private:
    int size_;
};

TEST(Clipmap, RandomFocusMovesEqualAFullRebuild) {
    constexpr int kSize = 16;
    constexpr int kLevels = 12;
    CoordinateTiles tiles(kSize);
    Clipmap incremental(kLevels, kSize, 2);
    std::mt19937 random(42);
    std::normal_distribution<double> step(0.0, 1.0);
    std::uniform_real_distribution<double> uniform(0.0, 1.0);
    double latitude = 0.3, longitude = 3.1;  // start next to the antimeridian
    const auto fetch = [&](const TileKey& key) { return tiles(key); };
    for (int move = 0; move < 400; ++move) {
        // Mostly small moves at various scales, sometimes a jump, sometimes to a pole.
        const double scale = std::ldexp(1.0, -int(uniform(random) * 12));
        latitude =
            std::clamp(latitude + step(random) * scale * 0.3, -kPi / 2 + 1e-6, kPi / 2 - 1e-6);
        longitude = std::remainder(longitude + step(random) * scale, 2 * kPi);
        if (uniform(random) < 0.03) {
            latitude = (uniform(random) < 0.5 ? 1 : -1) * (kPi / 2 - uniform(random) * 0.01);
        }
        for (int level = 0; level < kLevels; ++level) {
            ASSERT_TRUE(incremental.update(
                level, Clipmap::windowFor(level, latitude, longitude, kSize), fetch));
        }
        incremental.takeDirtyRegions();
    }
    Clipmap rebuilt(kLevels, kSize, 2);
    for (int level = 0; level < kLevels; ++level) {
        const ClipmapWindow window = Clipmap::windowFor(level, latitude, longitude, kSize);
        ASSERT_TRUE(rebuilt.update(level, window, fetch));
        EXPECT_EQ(incremental.window(level), window);
        EXPECT_EQ(incremental.data(level), rebuilt.data(level)) << "level " << level;
    }
}

TEST(Clipmap, TilesForCoverEveryFetchOfAnUpdate) {
    // The renderer requests tilesFor(window) ahead and updates only from those; any
    // fetch outside them would stall or fail. Random moves, poles and antimeridian.
    constexpr int kSize = 16;
    constexpr int kLevels = 10;
    CoordinateTiles tiles(kSize);
    Clipmap clipmap(kLevels, kSize, 2);
    std::mt19937 random(3);
    std::uniform_real_distribution<double> uniform(-1.0, 1.0);
    double latitude = 0.0, longitude = 3.13;
    for (int move = 0; move < 300; ++move) {
        latitude = std::clamp(latitude + uniform(random) * 0.2, -kPi / 2 + 1e-6, kPi / 2 - 1e-6);
        longitude = std::remainder(longitude + uniform(random) * 0.3, 2 * kPi);
        for (int level = 0; level < kLevels; ++level) {
            const ClipmapWindow window = Clipmap::windowFor(level, latitude, longitude, kSize);
            const std::vector<TileKey> allowed = Clipmap::tilesFor(window, kSize);
            EXPECT_LE(allowed.size(), 4u);
            const auto fetch = [&](const TileKey& key) {
                EXPECT_NE(std::find(allowed.begin(), allowed.end(), key), allowed.end())
                    << key.toString();
                return tiles(key);
            };
            ASSERT_TRUE(clipmap.update(level, window, fetch));
        }
        clipmap.takeDirtyRegions();
    }
}

TEST(Clipmap, TexelsHoldTheirGlobalCoordinates) {
    constexpr int kSize = 16;
    CoordinateTiles tiles(kSize);
    Clipmap clipmap(8, kSize, 2);
    const auto fetch = [&](const TileKey& key) { return tiles(key); };
    const double latitude = 0.2, longitude = -kPi + 1e-3;  // window wraps the antimeridian
    for (int level = 0; level < 8; ++level) {
        const ClipmapWindow w = Clipmap::windowFor(level, latitude, longitude, kSize);
        ASSERT_TRUE(clipmap.update(level, w, fetch));
        const std::int64_t columns = w.totalColumns(kSize);
        for (std::int64_t gy = w.originY; gy < w.originY + kSize; ++gy) {
            for (std::int64_t gx = w.originX; gx < w.originX + kSize; ++gx) {
                const std::int64_t wrapped = ((gx % columns) + columns) % columns;
                const std::int64_t row = std::clamp<std::int64_t>(gy, 0, w.totalRows(kSize) - 1);
                ASSERT_EQ(clipmap.texel(level, gx, gy, 0), float(wrapped + 1000 * w.lonReduction));
                ASSERT_EQ(clipmap.texel(level, gx, gy, 1), float(row + 100000 * w.level));
            }
        }
    }
}

TEST(Clipmap, SmallMoveCopiesOnlyTheStripsThatEntered) {
    constexpr int kSize = 64;
    CoordinateTiles tiles(kSize);
    Clipmap clipmap(12, kSize, 2);
    const auto fetch = [&](const TileKey& key) { return tiles(key); };
    const int level = 10;
    ClipmapWindow w = Clipmap::windowFor(level, 0.5, 0.5, kSize);
    ASSERT_TRUE(clipmap.update(level, w, fetch));
    clipmap.takeDirtyRegions();
    const std::uint64_t before = clipmap.texelsCopied();
    ClipmapWindow moved = w;
    moved.originX += 3;
    moved.originY -= 2;
    ASSERT_TRUE(clipmap.update(level, moved, fetch));
    // 2 full rows + 3 columns over the remaining 62 rows.
    EXPECT_EQ(clipmap.texelsCopied() - before, std::uint64_t(2 * kSize + 3 * (kSize - 2)));
    const std::vector<Clipmap::Region> regions = clipmap.takeDirtyRegions();
    EXPECT_GE(regions.size(), 2u);
    EXPECT_LE(regions.size(), 9u);  // seed 001 Fig. 4.3b: at most nine regions
}

TEST(Clipmap, WindowCoversTheRingAndWidensTowardsThePoles) {
    constexpr int kSize = 256;
    for (int level = 2; level < 24; ++level) {
        for (double latitude : {0.0, 0.8, 1.4, 1.5707}) {
            const ClipmapWindow w = Clipmap::windowFor(level, latitude, 1.0, kSize);
            const double radius = Clipmap::ringRadius(level);
            // Latitude: the window reaches at least one ring radius past the focus.
            EXPECT_GE(w.texelHeight(kSize) * (kSize / 2 - 1), radius);
            // Longitude: covers the spherical cap's half-width (or the whole circle).
            const double colatitude = kPi / 2 - latitude;
            if (radius < colatitude) {
                const double halfWidth = std::asin(std::sin(radius) / std::sin(colatitude));
                EXPECT_GE(w.texelWidth(kSize) * (kSize / 2 - 1), halfWidth)
                    << level << " " << latitude;
            } else {
                EXPECT_EQ(w.totalColumns(kSize), kSize) << level << " " << latitude;
            }
        }
    }
    // Near the pole the longitude texels are coarser than the latitude texels.
    const ClipmapWindow polar = Clipmap::windowFor(12, 1.55, 0.0, kSize);
    EXPECT_GT(polar.lonReduction, 0);
}

TEST(Clipmap, FailedFetchInvalidatesTheLevel) {
    Clipmap clipmap(4, 16, 1);
    const auto failing = [](const TileKey&) -> Result<TilePointer> {
        return Error{"disk on fire"};
    };
    const Status status = clipmap.update(2, Clipmap::windowFor(2, 0, 0, 16), failing);
    ASSERT_FALSE(status);
    EXPECT_EQ(status.error().message, "disk on fire");
    EXPECT_FALSE(clipmap.valid(2));
}

}  // namespace
}  // namespace sylva
