#include "sylva/core/sources/raster/NoiseSource.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "sylva/core/geo/Ellipsoid.h"
#include "sylva/core/scheduler/TileEvaluator.h"

namespace sylva {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

glm::dvec3 direction(double latitude, double longitude) {
    return {std::cos(latitude) * std::cos(longitude), std::cos(latitude) * std::sin(longitude),
            std::sin(latitude)};
}

TilePointer produce(const Source& source, const TileKey& key, TileFormat format = {16, 2}) {
    TileEvaluator evaluator(format);
    Result<TilePointer> tile = evaluator.tile(source, key);
    EXPECT_TRUE(tile) << tile.error().message;
    return tile ? tile.value() : nullptr;
}

TEST(NoiseSource, Deterministic) {
    NoiseParameters p;
    p.seed = 11;
    const NoiseSource a("a", p), b("b", p);
    const TileKey key{4, 0, 9, 5};
    const TilePointer ta = produce(a, key), tb = produce(b, key);
    ASSERT_TRUE(ta && tb);
    EXPECT_EQ(ta->texels(), tb->texels());
    // Not trivially constant.
    const auto [lo, hi] = std::minmax_element(ta->texels().begin(), ta->texels().end());
    EXPECT_GT(*hi - *lo, 1.0f);
}

TEST(NoiseSource, SeamlessAcrossTheAntimeridian) {
    const NoiseSource source("n", NoiseParameters{});
    const int level = 3;
    const int columns = TileKey::columns(level, 0);
    for (int y = 0; y < TileKey::rows(level); ++y) {
        const TilePointer last = produce(source, TileKey{level, 0, columns - 1, y});
        const TilePointer first = produce(source, TileKey{level, 0, 0, y});
        ASSERT_TRUE(last && first);
        const int size = last->size();
        for (int iy = -last->border(); iy < size + last->border(); ++iy) {
            for (int b = 0; b < last->border(); ++b) {
                // East border texel size + b of the last column is texel b of column 0.
                EXPECT_NEAR(last->at(size + b, iy, 0), first->at(b, iy, 0), 1e-3)
                    << "row " << y << " iy " << iy;
                // And the other way round: west border of column 0.
                EXPECT_NEAR(first->at(-1 - b, iy, 0), last->at(size - 1 - b, iy, 0), 1e-3)
                    << "row " << y << " iy " << iy;
            }
        }
    }
}

TEST(NoiseSource, ConvergesAtThePoles) {
    const NoiseSource source("n", NoiseParameters{});
    // The footprint of a level-3 tile texel (16 texels per tile): the finest octaves
    // such a tile contains.
    const TileKey key{3, 0, 0, 0};
    const double footprint = Ellipsoid::kMeanRadius * std::numbers::pi / TileKey::rows(3) / 16;
    for (double latitude : {89.999 * kDegree, -89.999 * kDegree}) {
        const double reference = source.height(direction(latitude, 0.0), footprint);
        for (int i = 1; i < 72; ++i) {
            const double longitude = -std::numbers::pi + i * 5.0 * kDegree;
            EXPECT_NEAR(source.height(direction(latitude, longitude), footprint), reference, 0.5)
                << "longitude " << longitude / kDegree;
        }
    }
    // The first row of the tile lies 1/32 of 22.5 degrees from the pole: its texels
    // all lie within a small circle, so they spread much less than a mid-latitude row.
    const TilePointer polar = produce(source, key);
    const TilePointer middle = produce(source, TileKey{3, 0, 0, 3});
    ASSERT_TRUE(polar && middle);
    const auto spread = [](const ImageTile& tile, int iy) {
        float lo = tile.at(0, iy, 0), hi = lo;
        for (int ix = 0; ix < tile.size(); ++ix) {
            lo = std::min(lo, tile.at(ix, iy, 0));
            hi = std::max(hi, tile.at(ix, iy, 0));
        }
        return hi - lo;
    };
    EXPECT_LT(spread(*polar, -polar->border()), 0.25f * spread(*middle, 0) + 1.0f);
}

TEST(NoiseSource, CoarseLevelsDifferByLessThanTheRemovedOctaves) {
    NoiseParameters p;
    p.ridges = 0.0;  // pure fBm: the removed amplitude is a geometric series
    const NoiseSource source("n", p);
    const TileKey coarse{2, 0, 3, 1};
    const TilePointer tile = produce(source, coarse);
    ASSERT_TRUE(tile);
    const double footprint =
        Ellipsoid::kMeanRadius * std::max(tile->texelHeight(), tile->texelWidth());
    // Octaves with wavelength below 4 footprints are (partly) faded out.
    double removed = 0.0, amplitude = 1.0, wavelength = p.baseWavelength;
    for (int octave = 0; octave < p.octaves; ++octave) {
        if (wavelength < 4.0 * footprint) {
            removed += amplitude;
        }
        amplitude *= p.gain;
        wavelength /= p.lacunarity;
    }
    // Gradient noise is "roughly" within [-1, 1]: allow 1.5.
    const double bound = 1.5 * p.amplitude * removed;
    ASSERT_GT(removed, 0.0);
    ASSERT_LT(bound, p.amplitude);
    double largest = 0.0;
    for (int iy = 0; iy < tile->size(); ++iy) {
        for (int ix = 0; ix < tile->size(); ++ix) {
            const glm::dvec3 d = direction(tile->texelLatitude(iy), tile->texelLongitude(ix));
            const double fine = source.height(d, 0.0);
            const double difference = std::abs(tile->at(ix, iy, 0) - fine);
            largest = std::max(largest, difference);
            EXPECT_LT(difference, bound) << ix << "," << iy;
        }
    }
    EXPECT_GT(largest, 0.0) << "the coarse tile was not band-limited at all";
    // A finer level keeps more octaves, so it is closer to the full surface.
    const TilePointer finer = produce(source, TileKey{2, 0, 3, 1}, TileFormat{64, 2});
    ASSERT_TRUE(finer);
    double largestFiner = 0.0;
    for (int iy = 0; iy < finer->size(); ++iy) {
        for (int ix = 0; ix < finer->size(); ++ix) {
            const glm::dvec3 d = direction(finer->texelLatitude(iy), finer->texelLongitude(ix));
            largestFiner =
                std::max(largestFiner, std::abs(finer->at(ix, iy, 0) - source.height(d, 0.0)));
        }
    }
    EXPECT_LT(largestFiner, largest);
}

TEST(NoiseSource, ContentHashFollowsParameters) {
    const NoiseParameters base;
    const NoiseSource a("a", base), b("b", base);
    EXPECT_EQ(a.contentHash(), b.contentHash());
    for (int which = 0; which < 6; ++which) {
        NoiseParameters p = base;
        switch (which) {
            case 0:
                p.seed = 2;
                break;
            case 1:
                p.amplitude = 2501;
                break;
            case 2:
                p.octaves = 12;
                break;
            case 3:
                p.ridges = 0.25;
                break;
            case 4:
                p.offset = -10;
                break;
            case 5:
                p.roughness = 0.5;
                break;
        }
        EXPECT_NE(NoiseSource("c", p).contentHash(), a.contentHash()) << "parameter " << which;
    }
}

}  // namespace
}  // namespace sylva
