// VegetationStream (issue 7): the instance tiles around the camera cover the streaming
// disc exactly once (no tile is inside another, every point of the disc is in one
// tile), finer near the camera, also across the antimeridian.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "sylva/core/vegetation/VegetationStream.h"

namespace sylva {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDegree = kPi / 180;

bool contains(const TileKey& key, double latitude, double longitude) {
    return latitude <= key.north() && latitude > key.south() && longitude >= key.west() &&
           longitude < key.east();
}

void checkCover(double latitude, double longitude, double radius) {
    const std::vector<TileKey> tiles =
        VegetationStream::tilesAround(latitude, longitude, radius, 8);
    ASSERT_FALSE(tiles.empty());
    int coarsest = 99, finest = -1;
    for (const TileKey& key : tiles) {
        coarsest = std::min(coarsest, key.level);
        finest = std::max(finest, key.level);
        EXPECT_EQ(key.lonReduction, 0);
    }
    EXPECT_LE(finest - coarsest, 2);
    // Points on a polar grid over the disc: each in exactly one tile.
    for (int ring = 0; ring <= 10; ++ring) {
        const double r = radius * 0.98 * ring / 10.0;
        for (int step = 0; step < 36; ++step) {
            const double bearing = step * 10 * kDegree;
            const double pointLatitude = latitude + r * std::cos(bearing) / 6367000.0;
            double pointLongitude =
                longitude + r * std::sin(bearing) / (6367000.0 * std::cos(latitude));
            if (pointLongitude >= kPi) {
                pointLongitude -= 2 * kPi;
            } else if (pointLongitude < -kPi) {
                pointLongitude += 2 * kPi;
            }
            int holders = 0;
            for (const TileKey& key : tiles) {
                holders += contains(key, pointLatitude, pointLongitude) ? 1 : 0;
            }
            EXPECT_EQ(holders, 1) << "point at " << r << " m, bearing " << step * 10;
        }
    }
    // The tile under the camera is one of the finest.
    for (const TileKey& key : tiles) {
        if (contains(key, latitude, longitude)) {
            EXPECT_EQ(key.level, finest);
        }
    }
}

TEST(VegetationStream, TilesCoverTheDiscOnceFinerNearTheCamera) {
    checkCover(-8.0 * kDegree, -34.9 * kDegree, 6000.0);
    checkCover(47.3 * kDegree, 8.5 * kDegree, 800.0);
    checkCover(12.0 * kDegree, 179.99 * kDegree, 3000.0);  // across the antimeridian
}

TEST(VegetationStream, NothingBeyondTheRadiusOrWhenTheRadiusIsZero) {
    EXPECT_TRUE(VegetationStream::tilesAround(0.1, 0.2, 0.0, 8).empty());
    const std::vector<TileKey> tiles = VegetationStream::tilesAround(0.1, 0.2, 1000.0, 8);
    EXPECT_LT(tiles.size(), 128u);
}

}  // namespace
}  // namespace sylva
