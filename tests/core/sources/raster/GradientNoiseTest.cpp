// GradientNoise against a plain transcription of its definition: Perlin's improved noise
// (2002) with the gradient chosen by a switch over the 16 cube-edge entries and each
// lattice corner hashed on its own. The optimised noise (a gradient table, the hash's
// per-axis products shared by the eight corners) must give the same value bit for bit
// (zeros of either sign count as equal), since every golden image of noise terrain
// depends on it. A second check: NoiseSource's tiles (weights once per row) equal its
// per-texel height().
#include "sylva/core/sources/raster/GradientNoise.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>

#include "sylva/core/scheduler/TileEvaluator.h"
#include "sylva/core/sources/raster/NoiseSource.h"

namespace sylva {
namespace {

std::uint32_t referenceHash(std::int64_t x, std::int64_t y, std::int64_t z, std::uint32_t seed) {
    std::uint64_t h = static_cast<std::uint64_t>(x) * 0x9E3779B97F4A7C15ull;
    h ^= static_cast<std::uint64_t>(y) * 0xC2B2AE3D27D4EB4Full;
    h ^= static_cast<std::uint64_t>(z) * 0x165667B19E3779F9ull;
    h ^= static_cast<std::uint64_t>(seed) * 0xD6E8FEB86659FD93ull;
    h ^= h >> 30;
    h *= 0xBF58476D1CE4E5B9ull;
    h ^= h >> 27;
    h *= 0x94D049BB133111EBull;
    h ^= h >> 31;
    return static_cast<std::uint32_t>(h);
}

double referenceGradient(std::uint32_t hash, double x, double y, double z) {
    switch (hash & 15u) {
        case 0:
            return x + y;
        case 1:
            return -x + y;
        case 2:
            return x - y;
        case 3:
            return -x - y;
        case 4:
            return x + z;
        case 5:
            return -x + z;
        case 6:
            return x - z;
        case 7:
            return -x - z;
        case 8:
            return y + z;
        case 9:
            return -y + z;
        case 10:
            return y - z;
        case 11:
            return -y - z;
        case 12:
            return x + y;
        case 13:
            return -y + z;
        case 14:
            return -x + y;
        default:
            return -y - z;
    }
}

double referenceNoise(const glm::dvec3& p, std::uint32_t seed) {
    const double fx = std::floor(p.x), fy = std::floor(p.y), fz = std::floor(p.z);
    const auto ix = static_cast<std::int64_t>(fx), iy = static_cast<std::int64_t>(fy),
               iz = static_cast<std::int64_t>(fz);
    const double x = p.x - fx, y = p.y - fy, z = p.z - fz;
    auto fade = [](double t) { return t * t * t * (t * (t * 6.0 - 15.0) + 10.0); };
    auto lerp = [](double a, double b, double t) { return a + t * (b - a); };
    auto corner = [&](int dx, int dy, int dz) {
        return referenceGradient(referenceHash(ix + dx, iy + dy, iz + dz, seed), x - dx, y - dy,
                                 z - dz);
    };
    const double u = fade(x), v = fade(y), w = fade(z);
    return lerp(lerp(lerp(corner(0, 0, 0), corner(1, 0, 0), u),
                     lerp(corner(0, 1, 0), corner(1, 1, 0), u), v),
                lerp(lerp(corner(0, 0, 1), corner(1, 0, 1), u),
                     lerp(corner(0, 1, 1), corner(1, 1, 1), u), v),
                w);
}

TEST(GradientNoise, EqualsItsDefinitionBitForBit) {
    std::mt19937_64 random(5);
    // Small and planet-scale coordinates (the finest octave spans 2^24 cells), negative too.
    std::uniform_real_distribution<double> small(-40.0, 40.0), large(-3.0e7, 3.0e7);
    for (std::uint32_t seed : {0u, 11u, 4000000000u}) {
        const GradientNoise noise(seed);
        for (int i = 0; i < 100000; ++i) {
            auto& d = i % 2 ? small : large;
            const glm::dvec3 p(d(random), d(random), d(random));
            const double expected = referenceNoise(p, seed);
            ASSERT_EQ(noise(p), expected)
                << "seed " << seed << " at " << p.x << ", " << p.y << ", " << p.z;
        }
        // Lattice points (zero) and cell faces.
        EXPECT_EQ(noise(glm::dvec3(3.0, -7.0, 12.0)), 0.0);
        EXPECT_EQ(noise(glm::dvec3(3.0, 0.5, 0.25)), referenceNoise({3.0, 0.5, 0.25}, seed));
    }
}

TEST(GradientNoise, NoiseTilesEqualPerTexelHeights) {
    NoiseParameters p;
    p.seed = 11;
    p.ridges = 0.7;
    p.ridgeWavelength = 12000.0;
    const NoiseSource source("n", p);
    const TileKey key{12, 0, 3001, 1450};
    TileEvaluator evaluator(TileFormat{32, 2});
    auto tile = evaluator.tile(source, key);
    ASSERT_TRUE(tile) << tile.error().message;
    const ImageTile& t = **tile;
    for (int iy = -2; iy < 34; iy += 5)
        for (int ix = -2; ix < 34; ix += 3) {
            const double latitude = t.texelLatitude(iy), longitude = t.texelLongitude(ix);
            const glm::dvec3 direction(std::cos(latitude) * std::cos(longitude),
                                       std::cos(latitude) * std::sin(longitude),
                                       std::sin(latitude));
            const double footprint =
                6371008.8 *
                std::max(t.texelHeight(), t.texelWidth() * std::abs(std::cos(latitude)));
            EXPECT_EQ(t.at(ix, iy, 0), static_cast<float>(source.height(direction, footprint)))
                << ix << ", " << iy;
        }
}

}  // namespace
}  // namespace sylva
