// The proposal and the terrain: `elevation_edit { mode = level }` levels a footprint at
// the mean ground height under it (against the analytic mean of a planar slope), and
// `plants { exclude = @footprints }` keeps every instance out of the footprints (an exact
// point-in-rectangle check) while scattering the rest as before.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include <unistd.h>

#include "sylva/core/base/Hash.h"
#include "sylva/core/geo/Ellipsoid.h"
#include "sylva/core/scheduler/TileEvaluator.h"
#include "sylva/core/sources/plants/PlantsSource.h"
#include "sylva/core/sources/raster/ConstantSource.h"
#include "sylva/core/sources/vector/ElevationEditSource.h"

namespace sylva {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
constexpr double kLatitude = 10.0, kLongitude = 20.0;  // degrees

std::filesystem::path square(const std::string& name, double half) {
    const auto folder =
        std::filesystem::temp_directory_path() / ("sylva-interplay-" + std::to_string(::getpid()));
    std::filesystem::create_directories(folder);
    const auto path = folder / name;
    const auto c = [](double v) { return std::to_string(v); };
    const double w = kLongitude - half, e = kLongitude + half, s = kLatitude - half,
                 n = kLatitude + half;
    std::ofstream(path) << R"({"type":"FeatureCollection","features":[{"type":"Feature","id":1,)"
                        << R"("properties":{},"geometry":{"type":"Polygon","coordinates":[[[)"
                        << c(w) << "," << c(s) << "],[" << c(e) << "," << c(s) << "],[" << c(e)
                        << "," << c(n) << "],[" << c(w) << "," << c(n) << "],[" << c(w) << ","
                        << c(s) << "]]]}}]}";
    return path;
}

// Height rising linearly with longitude: 100 m at kLongitude, 1 m per 0.001°.
class RampSource final : public Source {
public:
    RampSource() : Source("ramp", "test", PortType::Elevation, 1) {
        setParameterHash(ContentHash().add(std::string_view("ramp-v1")).value());
    }
    static double height(double longitude) {
        return 100.0 + (longitude / kDegree - kLongitude) * 1000.0;
    }
    Result<TilePointer> produce(const TileKey& key, TileProvider& provider) const override {
        const TileFormat& format = provider.format();
        auto tile = std::make_shared<ImageTile>(key, format.size, format.border, 1);
        for (int iy = -format.border; iy < format.size + format.border; ++iy) {
            for (int ix = -format.border; ix < format.size + format.border; ++ix) {
                tile->at(ix, iy, 0) = float(height(tile->texelLongitude(ix)));
            }
        }
        return TilePointer(tile);
    }
};

// Density 1 everywhere.
class FullMask final : public Source {
public:
    FullMask() : Source("full", "test", PortType::Mask, 1) {
        setParameterHash(ContentHash().add(std::string_view("full-v1")).value());
    }
    Result<TilePointer> produce(const TileKey& key, TileProvider& provider) const override {
        const TileFormat& format = provider.format();
        auto tile = std::make_shared<ImageTile>(key, format.size, format.border, 1);
        for (int iy = -format.border; iy < format.size + format.border; ++iy) {
            for (int ix = -format.border; ix < format.size + format.border; ++ix) {
                tile->at(ix, iy, 0) = 1.0f;
            }
        }
        return TilePointer(tile);
    }
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

TEST(TerrainInterplay, LevelModeFlattensAFootprintAtTheMeanGroundHeight) {
    const RampSource ramp;
    FeatureSource plot("plot", square("plot.geojson", 0.0002), {});
    ElevationEditParameters p;
    p.mode = ElevationEditParameters::Mode::Level;
    p.amount = 0.5;
    const ElevationEditSource levelled("levelled", &ramp, &plot, p);
    TileEvaluator evaluator(TileFormat{256, 2});
    const TileKey key = keyAt(15, kLongitude, kLatitude);
    Result<TilePointer> tile = evaluator.tile(levelled, key);
    ASSERT_TRUE(tile) << tile.error().message;
    // The ramp's mean over the four corners and the centroid is its value at the centre.
    int inside = 0, outside = 0;
    for (int iy = 0; iy < 256; ++iy) {
        for (int ix = 0; ix < 256; ++ix) {
            const double lon = tile.value()->texelLongitude(ix) / kDegree;
            const double lat = tile.value()->texelLatitude(iy) / kDegree;
            const float h = tile.value()->at(ix, iy, 0);
            if (std::abs(lon - kLongitude) < 0.00018 && std::abs(lat - kLatitude) < 0.00018) {
                EXPECT_NEAR(h, 100.5, 0.01);
                ++inside;
            } else if (std::abs(lon - kLongitude) > 0.00022 ||
                       std::abs(lat - kLatitude) > 0.00022) {
                EXPECT_NEAR(h, RampSource::height(lon * kDegree), 0.01);
                ++outside;
            }
        }
    }
    EXPECT_GT(inside, 100);
    EXPECT_GT(outside, 1000);
}

TEST(TerrainInterplay, PlantsAreKeptOutOfExcludedFootprints) {
    const ConstantSource ground("ground", 0.0);
    const FullMask full;
    FeatureSource footprint("footprint", square("footprint.geojson", 0.0005), {});
    PlantsParameters p;
    p.perHectare = 400;
    p.species = {{"oak", 1.0}};
    p.seed = 3;
    Result<std::unique_ptr<PlantsSource>> open =
        PlantsSource::make("open", &ground, &full, nullptr, p);
    Result<std::unique_ptr<PlantsSource>> cleared =
        PlantsSource::make("cleared", &ground, &full, nullptr, p);
    ASSERT_TRUE(open && cleared);
    cleared.value()->excludeInside(&footprint);
    EXPECT_NE(open.value()->contentHash(), cleared.value()->contentHash());
    TileEvaluator evaluator(TileFormat{64, 2});
    const TileKey key = keyAt(16, kLongitude, kLatitude);
    Result<std::shared_ptr<const InstanceTile>> all = open.value()->instances(key, evaluator);
    Result<std::shared_ptr<const InstanceTile>> kept = cleared.value()->instances(key, evaluator);
    ASSERT_TRUE(all && kept);
    const auto inside = [](const PlantInstance& i) {
        return std::abs(i.longitude / kDegree - kLongitude) < 0.0005 &&
               std::abs(i.latitude / kDegree - kLatitude) < 0.0005;
    };
    std::size_t insideBefore = 0;
    for (const PlantInstance& instance : all.value()->instances) {
        insideBefore += inside(instance);
    }
    ASSERT_GT(insideBefore, 50u);
    for (const PlantInstance& instance : kept.value()->instances) {
        EXPECT_FALSE(inside(instance));
    }
    EXPECT_EQ(kept.value()->instances.size() + insideBefore, all.value()->instances.size());
}

}  // namespace
}  // namespace sylva
