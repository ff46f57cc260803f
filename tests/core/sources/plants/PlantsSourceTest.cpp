#include "sylva/core/sources/plants/PlantsSource.h"

#include <gtest/gtest.h>

#include <GeographicLib/Geodesic.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <numbers>
#include <set>
#include <thread>
#include <tuple>

#include <unistd.h>

#include "sylva/core/scheduler/TileEvaluator.h"
#include "sylva/core/sources/compose/RasterizeSource.h"
#include "sylva/core/sources/raster/ConstantSource.h"
#include "sylva/core/sources/vector/CoverageRasterizer.h"

namespace sylva {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

// A mask given as a function of (latitude, longitude) in radians.
class FunctionMask final : public Source {
public:
    FunctionMask(std::uint64_t tag, std::function<float(double, double)> f)
        : Source("density", "function", PortType::Mask, 1), f_(std::move(f)) {
        setParameterHash(tag);
    }
    Result<TilePointer> produce(const TileKey& key, TileProvider& provider) const override {
        const TileFormat& format = provider.format();
        auto tile = std::make_shared<ImageTile>(key, format.size, format.border, 1);
        for (int iy = -format.border; iy < format.size + format.border; ++iy) {
            for (int ix = -format.border; ix < format.size + format.border; ++ix) {
                tile->at(ix, iy, 0) = f_(tile->texelLatitude(iy), tile->texelLongitude(ix));
            }
        }
        return TilePointer(std::move(tile));
    }

private:
    std::function<float(double, double)> f_;
};

TileKey keyAt(int level, double lonDeg, double latDeg) {
    TileKey key;
    key.level = level;
    key.x = int(
        std::floor((lonDeg * kDegree + std::numbers::pi) / (2 * std::numbers::pi) * key.columns()));
    key.y =
        int(std::floor((std::numbers::pi / 2 - latDeg * kDegree) / std::numbers::pi * key.rows()));
    return key;
}

std::unique_ptr<PlantsSource> scatter(const Source& ground, const Source& density,
                                      double perHectare, double spacing) {
    PlantsParameters p;
    p.perHectare = perHectare;
    p.spacing = spacing;
    p.species = {{"oak", 0.6}, {"pine", 0.4}};
    p.seed = 42;
    Result<std::unique_ptr<PlantsSource>> made =
        PlantsSource::make("forest", &ground, &density, nullptr, p);
    SYLVA_CHECK(made);
    return std::move(made.value());
}

using Position = std::pair<double, double>;

std::vector<PlantInstance> block(const PlantsSource& plants, TileProvider& provider, TileKey centre,
                                 int radius, bool reverse = false) {
    std::vector<PlantInstance> all;
    std::vector<TileKey> keys;
    for (int dy = -radius; dy <= radius; ++dy) {
        for (int dx = -radius; dx <= radius; ++dx) {
            TileKey k = centre;
            k.x += dx;
            k.y += dy;
            keys.push_back(k);
        }
    }
    if (reverse) {
        std::reverse(keys.begin(), keys.end());
    }
    for (const TileKey& k : keys) {
        Result<std::shared_ptr<const InstanceTile>> tile = plants.instances(k, provider);
        SYLVA_CHECK(tile);
        for (const PlantInstance& instance : tile.value()->instances) {
            // Each instance lies in the tile that holds it.
            EXPECT_GE(instance.longitude, k.west());
            EXPECT_LT(instance.longitude, k.east());
            EXPECT_GE(instance.latitude, k.south());
            EXPECT_LT(instance.latitude, k.north());
            all.push_back(instance);
        }
    }
    return all;
}

TEST(PlantsSource, DensityMatchesRequestAndSpeciesShares) {
    for (const double latitude : {3.0, 48.0, -66.0}) {
        const ConstantSource ground("ground", 123.0);
        // Half density in the western half of every tile column pattern: a smooth mask.
        const FunctionMask mask(
            1, [](double, double lon) { return float(0.5 + 0.5 * std::sin(lon * 20000.0)); });
        auto plants = scatter(ground, mask, 80.0, 4.0);
        TileEvaluator evaluator(TileFormat{64, 2});
        const TileKey centre = keyAt(15, 20.0, latitude);
        const std::vector<PlantInstance> all = block(*plants, evaluator, centre, 1);
        // Expected: integral of mask x density over the 3 x 3 tiles, by texel sums.
        double expected = 0.0;
        for (int dy = -1; dy <= 1; ++dy) {
            for (int dx = -1; dx <= 1; ++dx) {
                TileKey k = centre;
                k.x += dx;
                k.y += dy;
                const ImageTile& m = *evaluator.tile(mask, k).value();
                for (int iy = 0; iy < 64; ++iy) {
                    const double north = k.north() - iy * m.texelHeight();
                    const double area = CoverageRasterizer::quadrangleArea(north - m.texelHeight(),
                                                                           north, m.texelWidth());
                    for (int ix = 0; ix < 64; ++ix) {
                        expected += m.at(ix, iy, 0) * area * 80.0 / 1e4;
                    }
                }
            }
        }
        ASSERT_GT(expected, 3000.0);
        EXPECT_NEAR(double(all.size()) / expected, 1.0, 0.05) << "latitude " << latitude;
        EXPECT_NEAR(double(all.size()) / expected, 1.0, 0.03) << "latitude " << latitude;
        std::size_t oaks = 0;
        for (const PlantInstance& instance : all) {
            oaks += instance.species == 0;
            EXPECT_EQ(instance.height, 123.0);
            EXPECT_GE(instance.scale, 0.8f);
            EXPECT_LE(instance.scale, 1.2f);
        }
        EXPECT_NEAR(double(oaks) / double(all.size()), 0.6, 0.03);
    }
}

TEST(PlantsSource, UniqueAcrossBordersAndMinimumSpacingHeld) {
    const ConstantSource ground("ground", 0.0);
    const FunctionMask full(2, [](double, double) { return 1.0f; });
    const double spacing = 6.5;
    auto plants = scatter(ground, full, 150.0, spacing);
    TileEvaluator evaluator(TileFormat{64, 2});
    const TileKey centre = keyAt(16, -34.9, -8.0);
    const std::vector<PlantInstance> all = block(*plants, evaluator, centre, 1);
    ASSERT_GT(all.size(), 2000u);
    std::set<Position> unique;
    for (const PlantInstance& i : all) {
        unique.insert({i.longitude, i.latitude});
    }
    EXPECT_EQ(unique.size(), all.size()) << "an instance appears in two tiles";
    // Minimum geodesic spacing among neighbours (a hash grid of ~spacing cells).
    const GeographicLib::Geodesic& geodesic = GeographicLib::Geodesic::WGS84();
    std::map<std::pair<long, long>, std::vector<const PlantInstance*>> grid;
    const double cell = 10.0 / 6.4e6;
    for (const PlantInstance& i : all) {
        grid[{long(std::floor(i.longitude / cell)), long(std::floor(i.latitude / cell))}].push_back(
            &i);
    }
    double nearest = 1e9;
    for (const auto& [at, items] : grid) {
        for (const PlantInstance* a : items) {
            for (long dy = -1; dy <= 1; ++dy) {
                for (long dx = -1; dx <= 1; ++dx) {
                    auto it = grid.find({at.first + dx, at.second + dy});
                    if (it == grid.end()) {
                        continue;
                    }
                    for (const PlantInstance* b : it->second) {
                        if (a == b) {
                            continue;
                        }
                        double distance = 0.0;
                        geodesic.Inverse(a->latitude / kDegree, a->longitude / kDegree,
                                         b->latitude / kDegree, b->longitude / kDegree, distance);
                        nearest = std::min(nearest, distance);
                    }
                }
            }
        }
    }
    EXPECT_GE(nearest, spacing * (1.0 - 1e-9));
    EXPECT_LT(nearest, 2.0 * spacing);  // a dense pattern, not a sparse one
    // instancesNear of the centre tile contains exactly its own instances plus neighbours'.
    Result<std::vector<PlantInstance>> near = plants->instancesNear(centre, 20.0, evaluator);
    ASSERT_TRUE(near);
    std::set<Position> nearSet;
    for (const PlantInstance& i : near.value()) {
        nearSet.insert({i.longitude, i.latitude});
    }
    const std::shared_ptr<const InstanceTile> centreTile =
        plants->instances(centre, evaluator).value();
    for (const PlantInstance& i : centreTile->instances) {
        EXPECT_EQ(nearSet.count({i.longitude, i.latitude}), 1u);
    }
    for (const Position& p : nearSet) {
        EXPECT_EQ(unique.count(p), 1u) << "instancesNear invented an instance";
    }
}

TEST(PlantsSource, SeamlessAcrossTheAntimeridian) {
    const ConstantSource ground("ground", 0.0);
    const FunctionMask full(2, [](double, double) { return 1.0f; });
    auto plants = scatter(ground, full, 100.0, 4.0);
    TileEvaluator evaluator(TileFormat{64, 2});
    TileKey east = keyAt(17, 179.999, -17.0);  // Fiji
    ASSERT_EQ(east.x, east.columns() - 1);
    TileKey west = east;
    west.x = 0;
    const std::shared_ptr<const InstanceTile> eastTile = plants->instances(east, evaluator).value();
    const std::shared_ptr<const InstanceTile> westTile = plants->instances(west, evaluator).value();
    ASSERT_GT(eastTile->instances.size(), 100u);
    ASSERT_GT(westTile->instances.size(), 100u);
    // Instances near the line from the other side, with wrapped longitudes.
    Result<std::vector<PlantInstance>> near = plants->instancesNear(west, 30.0, evaluator);
    ASSERT_TRUE(near);
    std::set<Position> fromEast;
    for (const PlantInstance& i : eastTile->instances) {
        fromEast.insert({i.longitude, i.latitude});
    }
    int crossing = 0;
    for (const PlantInstance& i : near.value()) {
        if (i.longitude > 0.0 && i.latitude >= east.south() && i.latitude < east.north()) {
            EXPECT_EQ(fromEast.count({i.longitude, i.latitude}), 1u);
            ++crossing;
        }
    }
    EXPECT_GT(crossing, 0);
    // Spacing holds across the line.
    const GeographicLib::Geodesic& geodesic = GeographicLib::Geodesic::WGS84();
    for (const PlantInstance& a : eastTile->instances) {
        for (const PlantInstance& b : westTile->instances) {
            if (a.longitude < std::numbers::pi - 1e-5 || b.longitude > -std::numbers::pi + 1e-5) {
                continue;
            }
            double distance = 0.0;
            geodesic.Inverse(a.latitude / kDegree, a.longitude / kDegree, b.latitude / kDegree,
                             b.longitude / kDegree, distance);
            EXPECT_GE(distance, 4.0);
        }
    }
}

TEST(PlantsSource, IdenticalAcrossRunsOrdersAndThreads) {
    const ConstantSource ground("ground", 10.0);
    const FunctionMask mask(
        3, [](double lat, double) { return float(0.3 + 0.7 * std::abs(std::sin(lat * 5000.0))); });
    auto plants = scatter(ground, mask, 60.0, 3.0);
    const TileKey centre = keyAt(15, 135.0, 35.0);
    auto key = [](const PlantInstance& i) {
        return std::make_tuple(i.longitude, i.latitude, i.species, i.scale, i.rotation, i.tint.x,
                               i.height);
    };
    auto run = [&](bool reverse) {
        TileEvaluator evaluator(TileFormat{64, 2});
        std::vector<std::tuple<double, double, std::uint32_t, float, float, float, double>> out;
        for (const PlantInstance& i : block(*plants, evaluator, centre, 1, reverse)) {
            out.push_back(key(i));
        }
        std::sort(out.begin(), out.end());
        return out;
    };
    const auto first = run(false);
    EXPECT_EQ(first, run(true));
    std::vector<decltype(run(false))> results(4);
    std::vector<std::thread> threads;
    for (int t = 0; t < 4; ++t) {
        threads.emplace_back([&, t] { results[std::size_t(t)] = run(t % 2 == 1); });
    }
    for (std::thread& t : threads) {
        t.join();
    }
    for (const auto& r : results) {
        EXPECT_EQ(r, first);
    }
    ASSERT_GT(first.size(), 1000u);
    // A tile's instances are exactly those of its four children.
    TileEvaluator evaluator(TileFormat{64, 2});
    std::vector<std::tuple<double, double, std::uint32_t, float, float, float, double>> parent,
        children;
    const std::shared_ptr<const InstanceTile> parentTile =
        plants->instances(centre, evaluator).value();
    for (const PlantInstance& i : parentTile->instances) {
        parent.push_back(key(i));
    }
    for (int c = 0; c < 4; ++c) {
        TileKey child = centre;
        child.level += 1;
        child.x = 2 * centre.x + (c & 1);
        child.y = 2 * centre.y + (c >> 1);
        const std::shared_ptr<const InstanceTile> childTile =
            plants->instances(child, evaluator).value();
        for (const PlantInstance& i : childTile->instances) {
            children.push_back(key(i));
        }
    }
    std::sort(parent.begin(), parent.end());
    std::sort(children.begin(), children.end());
    EXPECT_EQ(parent, children);
}

std::filesystem::path writeGeoJson(const std::string& name, const std::string& text) {
    const auto folder =
        std::filesystem::temp_directory_path() / ("sylva-plants-" + std::to_string(::getpid()));
    std::filesystem::create_directories(folder);
    const auto path = folder / name;
    std::ofstream(path) << text;
    return path;
}

TEST(PlantsSource, PointsWithSpeciesMappingAndErrors) {
    const auto path = writeGeoJson(
        "trees.geojson",
        R"({"type":"FeatureCollection","features":[)"
        R"({"type":"Feature","properties":{"genus":"Quercus","size":"1.5","heading":"90"},"geometry":{"type":"Point","coordinates":[10.0001,50.0001]}},)"
        R"({"type":"Feature","properties":{"genus":"Pinus","size":"0.7","heading":"0"},"geometry":{"type":"Point","coordinates":[10.0002,50.0002]}}]})");
    FeatureSource features("trees", path, {});
    const ConstantSource ground("ground", 250.0);
    PlantsParameters p;
    p.speciesAttribute = "genus";
    p.speciesMap = {{"Quercus", "oak"}};
    p.scaleAttribute = "size";
    p.rotationAttribute = "heading";
    Result<std::unique_ptr<PlantsSource>> made =
        PlantsSource::make("trees", &ground, nullptr, &features, p);
    ASSERT_TRUE(made) << made.error().message;
    TileEvaluator evaluator(TileFormat{64, 2});
    const TileKey key = keyAt(14, 10.0001, 50.0001);
    Result<std::shared_ptr<const InstanceTile>> missing = made.value()->instances(key, evaluator);
    ASSERT_FALSE(missing);
    // Instance tiles come through the provider, which names the source and tile.
    EXPECT_EQ(missing.error().message,
              "source 'trees', tile " + key.toString() + ": " + path.string() +
                  ": feature 1: species 'Pinus' (attribute 'genus') is not in species_map");
    p.speciesMap.push_back({"Pinus", "pine"});
    made = PlantsSource::make("trees", &ground, nullptr, &features, p);
    ASSERT_TRUE(made);
    Result<std::shared_ptr<const InstanceTile>> tile = made.value()->instances(key, evaluator);
    ASSERT_TRUE(tile) << tile.error().message;
    ASSERT_EQ(tile.value()->instances.size(), 2u);
    const PlantInstance& oak = tile.value()->instances[0];
    EXPECT_EQ(tile.value()->species[oak.species], "oak");
    EXPECT_FLOAT_EQ(oak.scale, 1.5f);
    EXPECT_FLOAT_EQ(oak.rotation, float(90 * kDegree));
    EXPECT_EQ(oak.height, 250.0);
    EXPECT_NEAR(oak.longitude, 10.0001 * kDegree, 1e-15);
    EXPECT_EQ(tile.value()->species[tile.value()->instances[1].species], "pine");
}

TEST(PlantsSource, SpacingLargerThanCellsIsAnError) {
    const ConstantSource ground("ground", 0.0);
    const FunctionMask full(2, [](double, double) { return 1.0f; });
    PlantsParameters p;
    p.perHectare = 100.0;
    p.spacing = 12.0;
    p.species = {{"oak", 1.0}};
    Result<std::unique_ptr<PlantsSource>> made =
        PlantsSource::make("f", &ground, &full, nullptr, p);
    ASSERT_FALSE(made);
    EXPECT_EQ(made.error().message,
              "spacing 12 m must be less than the cell size 9.9 m that per_hectare 100 gives");
}

// Crown markers of `plants`: 3 m discs, coverage only (no image).
std::unique_ptr<RasterizeSource> crownMarkers(const std::string& name, const PlantsSource& plants) {
    RasterizeParameters p;
    p.image = false;
    p.pointRadius = 3.0;
    return std::make_unique<RasterizeSource>(name, nullptr, &plants, p);
}

// Channel 0 summed over the interior texels of a 64 x 64 tile.
double coveredTexels(const ImageTile& tile) {
    double covered = 0.0;
    for (int iy = 0; iy < 64; ++iy) {
        for (int ix = 0; ix < 64; ++ix) {
            covered += tile.at(ix, iy, 0);
        }
    }
    return covered;
}

TEST(PlantsSource, RasterizedCrownsAreSeamless) {
    const ConstantSource ground("ground", 0.0);
    const FunctionMask full(2, [](double, double) { return 1.0f; });
    auto plants = scatter(ground, full, 40.0, 5.0);
    const std::unique_ptr<RasterizeSource> crowns = crownMarkers("crowns", *plants);
    TileEvaluator evaluator(TileFormat{64, 2});
    const TileKey a = keyAt(17, 2.0, 41.0);
    TileKey b = a;
    b.x += 1;
    const ImageTile& left = *evaluator.tile(*crowns, a).value();
    const ImageTile& right = *evaluator.tile(*crowns, b).value();
    // The right border of `left` equals the first columns of `right`.
    for (int iy = 0; iy < 64; ++iy) {
        for (int i = 0; i < 2; ++i) {
            EXPECT_NEAR(left.at(64 + i, iy, 0), right.at(i, iy, 0), 1e-6);
            EXPECT_NEAR(right.at(-1 - i, iy, 0), left.at(63 - i, iy, 0), 1e-6);
        }
    }
    const double covered = coveredTexels(left);
    // Crown cover ~ density x pi r^2 x scale^2 (1 - overlap): between 15 % and 15 % x 1.1.
    EXPECT_GT(covered / (64 * 64), 0.08);
    EXPECT_LT(covered / (64 * 64), 0.16);
}

// Flat ground at 7 m that counts the tiles it produced.
class CountingGround final : public Source {
public:
    CountingGround() : Source("ground", "counting", PortType::Elevation, 1) { setParameterHash(7); }
    Result<TilePointer> produce(const TileKey& key, TileProvider& provider) const override {
        ++calls;
        const TileFormat& format = provider.format();
        auto tile = std::make_shared<ImageTile>(key, format.size, format.border, 1);
        for (float& t : tile->texels()) {
            t = 7.0f;
        }
        return TilePointer(std::move(tile));
    }
    mutable std::atomic<int> calls{0};
};

TEST(PlantsSource, ElevationIsReadOnlyWhereInstancesAreKeptAndNeverForMarkers) {
    // Issue 20: a colour tile of level 11 with rasterized markers made its worker produce
    // the elevation chain of every sample tile under it (30-60 tiles of fractal noise,
    // 15-30 s), though markers are drawn in plan and most sample tiles hold no forest.
    const CountingGround ground;
    // Forest only east of 2.01°: the western sample tiles hold no instance.
    const FunctionMask east(3,
                            [](double, double lon) { return lon > 2.01 * kDegree ? 1.0f : 0.0f; });
    auto plants = scatter(ground, east, 40.0, 5.0);
    const std::unique_ptr<RasterizeSource> markers = crownMarkers("markers", *plants);
    TileEvaluator evaluator(TileFormat{64, 2});
    const int level = std::max(plants->minimumLevel(), plants->sampleLevel() - 3);
    TileKey key = keyAt(level, 2.0, 41.0);
    ASSERT_LT(key.west(), 2.01 * kDegree);
    ASSERT_GT(key.east(), 2.01 * kDegree);
    Result<TilePointer> drawn = evaluator.tile(*markers, key);
    ASSERT_TRUE(drawn);
    EXPECT_GT(coveredTexels(*drawn.value()), 0.0);  // markers were drawn...
    EXPECT_EQ(ground.calls.load(), 0);              // ...without a single elevation tile
    // Instance tiles (what the vegetation renderer draws) carry heights, read only from
    // the sample tiles that hold instances: fewer than the tiles the density was read in.
    Result<std::shared_ptr<const InstanceTile>> tile = plants->instances(key, evaluator);
    ASSERT_TRUE(tile);
    ASSERT_FALSE(tile.value()->instances.empty());
    for (const PlantInstance& instance : tile.value()->instances) {
        EXPECT_FLOAT_EQ(float(instance.height), 7.0f);
    }
    const int samples = 1 << (plants->sampleLevel() - level);  // per side of the tile
    EXPECT_GT(ground.calls.load(), 0);
    EXPECT_LT(ground.calls.load(), samples * samples);
}

}  // namespace
}  // namespace sylva
