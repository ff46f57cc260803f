#include "sylva/bench/VectorBenchmark.h"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <numbers>
#include <random>
#include <vector>

#include "sylva/core/geo/Geodesy.h"
#include "sylva/core/scheduler/TileEvaluator.h"
#include "sylva/core/sources/compose/RasterizeSource.h"
#include "sylva/core/sources/plants/PlantsSource.h"
#include "sylva/core/sources/raster/ConstantSource.h"
#include "sylva/core/sources/raster/MaskSource.h"

namespace sylva::bench {

namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

// Tiles of `level` over a 0.5° square near Olinda.
std::vector<TileKey> benchTiles(int level) {
    std::vector<TileKey> keys;
    TileKey probe;
    probe.level = level;
    auto column = [&](double lon) {
        return int(std::floor((lon * kDegree + std::numbers::pi) / (2 * std::numbers::pi) *
                              probe.columns()));
    };
    auto row = [&](double lat) {
        return int(
            std::floor((std::numbers::pi / 2 - lat * kDegree) / std::numbers::pi * probe.rows()));
    };
    for (int y = row(-7.75); y <= row(-8.25); ++y) {
        for (int x = column(-35.25); x <= column(-34.75); ++x) {
            TileKey key = probe;
            key.x = x;
            key.y = y;
            keys.push_back(key);
        }
    }
    return keys;
}

// `polygons` random 64-gons (0.2–2 km radius) over the square, as GeoJSON text.
std::string polygonsGeoJson(int polygons) {
    std::mt19937 random(5);
    std::uniform_real_distribution<double> lon(-35.25, -34.75), lat(-8.25, -7.75),
        radius(200.0, 2000.0);
    std::string text = R"({"type":"FeatureCollection","features":[)";
    for (int i = 0; i < polygons; ++i) {
        const double cLat = lat(random) * kDegree, cLon = lon(random) * kDegree, r = radius(random);
        text += i ? "," : "";
        text +=
            R"({"type":"Feature","properties":{},"geometry":{"type":"Polygon","coordinates":[[)";
        for (int k = 0; k <= 64; ++k) {
            double pLat = 0.0, pLon = 0.0;
            Geodesy::destination(cLat, cLon, 2 * std::numbers::pi * (k % 64) / 64, r, pLat, pLon);
            text += k ? "," : "";
            text += "[";
            text += std::to_string(pLon / kDegree);
            text += ",";
            text += std::to_string(pLat / kDegree);
            text += "]";
        }
        text += "]]}}";
    }
    text += "]}";
    return text;
}

// Runs `pass` once; the count it returns per second of wall time.
double ratePerSecond(const std::function<int()>& pass, int& count) {
    const auto start = std::chrono::steady_clock::now();
    count = pass();
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return count / seconds;
}

// rasterize_tiles_per_s
Result<double> rasterizeRate(int polygons) {
    const std::filesystem::path file =
        std::filesystem::temp_directory_path() / "sylva-bench-vector.geojson";
    {
        std::ofstream stream(file, std::ios::trunc);
        stream << polygonsGeoJson(polygons);
        if (!stream) {
            return Error{file.string() + ": cannot write the benchmark's polygons"};
        }
    }
    FeatureSource features("polygons", file, {});
    RasterizeParameters parameters;
    parameters.outline = 20.0;
    RasterizeSource rasterize("rasterize", &features, nullptr, parameters);
    if (Result<std::shared_ptr<const FeatureCollection>> loaded = features.collection(); !loaded) {
        return loaded.error();
    }
    int count = 0;
    const double rate = ratePerSecond(
        [&] {
            TileEvaluator evaluator(TileFormat{256, 2});
            int produced = 0;
            for (int level = 11; level <= 13; ++level) {
                for (const TileKey& key : benchTiles(level)) {
                    produced += evaluator.tile(rasterize, key) ? 1 : 0;
                }
            }
            return produced;
        },
        count);
    std::error_code ignored;
    std::filesystem::remove(file, ignored);
    return rate;
}

// plants_tiles_per_s_level14 and plants_instances_per_tile
Result<std::pair<double, double>> plantsRate(int plantTiles) {
    const ConstantSource ground("ground", 20.0);
    const ConstantSource grey("grey", glm::vec4(0.5f, 0.5f, 0.5f, 1.0f));
    MaskParameters maskParameters;
    maskParameters.expression = "0.8";
    Result<std::unique_ptr<MaskSource>> mask = MaskSource::make("density", {&grey}, maskParameters);
    if (!mask) {
        return mask.error();
    }
    PlantsParameters plantsParameters;
    plantsParameters.perHectare = 150.0;
    plantsParameters.spacing = 3.0;
    plantsParameters.species = {{"broadleaf", 0.7}, {"palm", 0.3}};
    Result<std::unique_ptr<PlantsSource>> plants =
        PlantsSource::make("plants", &ground, mask.value().get(), nullptr, plantsParameters);
    if (!plants) {
        return plants.error();
    }
    std::size_t instances = 0;
    int tiles = 0;
    const double rate = ratePerSecond(
        [&] {
            TileEvaluator evaluator(TileFormat{256, 2});
            int count = 0;
            for (const TileKey& key : benchTiles(14)) {
                if (count == plantTiles) {
                    break;
                }
                Result<std::shared_ptr<const InstanceTile>> tile =
                    plants.value()->instances(key, evaluator);
                if (tile) {
                    instances += tile.value()->instances.size();
                    ++count;
                }
            }
            return count;
        },
        tiles);
    return std::make_pair(rate, tiles ? double(instances) / tiles : 0.0);
}

}  // namespace

std::string VectorBenchmarkResult::json() const {
    return metricsJson("vector", metrics, {NumberFormat::Notation::Fixed, 3});
}

Result<VectorBenchmarkResult> runVectorBenchmark(const VectorBenchmarkOptions& options) {
    VectorBenchmarkResult result;
    Result<double> rasterize = rasterizeRate(options.polygons);
    if (!rasterize) {
        return rasterize.error();
    }
    result.metrics.emplace_back("rasterize_tiles_per_s", rasterize.value());
    Result<std::pair<double, double>> plants = plantsRate(options.plantTiles);
    if (!plants) {
        return plants.error();
    }
    result.metrics.emplace_back("plants_tiles_per_s_level14", plants->first);
    result.metrics.emplace_back("plants_instances_per_tile", plants->second);
    return result;
}

}  // namespace sylva::bench
