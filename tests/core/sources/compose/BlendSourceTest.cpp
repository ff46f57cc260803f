#include "sylva/core/sources/compose/BlendSource.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <numbers>

#include <cpl_conv.h>
#include <gdal.h>
#include <ogr_srs_api.h>
#include <unistd.h>

#include "sylva/core/scheduler/TileEvaluator.h"
#include "sylva/core/sources/GdalDatasetPool.h"
#include "sylva/core/sources/raster/ConstantSource.h"
#include "sylva/core/sources/raster/RasterSource.h"

namespace sylva {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

// A mask given as a function of (latitude, longitude) in radians.
class FunctionMask final : public Source {
public:
    FunctionMask(std::uint64_t tag, std::function<double(double, double)> f)
        : Source("m", "function", PortType::Mask, 1), f_(std::move(f)) {
        setParameterHash(tag);
    }
    Result<TilePointer> produce(const TileKey& key, TileProvider& provider) const override {
        const TileFormat& format = provider.format();
        auto tile = std::make_shared<ImageTile>(key, format.size, format.border, 1);
        for (int iy = -format.border; iy < format.size + format.border; ++iy) {
            for (int ix = -format.border; ix < format.size + format.border; ++ix) {
                tile->at(ix, iy, 0) =
                    static_cast<float>(f_(tile->texelLatitude(iy), tile->texelLongitude(ix)));
            }
        }
        return TilePointer(std::move(tile));
    }

private:
    std::function<double(double, double)> f_;
};

TEST(BlendSource, ImageModesMatchDirectFormulas) {
    const glm::vec4 b(0.2f, 0.4f, 0.6f, 1.0f), o(0.5f, 0.25f, 1.0f, 0.5f);
    const ConstantSource base("base", b), over("over", o);
    TileEvaluator evaluator(TileFormat{8, 2});
    const double w = 0.8 * 0.5;  // opacity x over's alpha
    const std::pair<BlendMode, std::function<double(double, double)>> cases[] = {
        {BlendMode::Normal, [](double, double y) { return y; }},
        {BlendMode::Multiply, [](double x, double y) { return x * y; }},
        {BlendMode::Screen, [](double x, double y) { return 1 - (1 - x) * (1 - y); }},
        {BlendMode::Add, [](double x, double y) { return x + y; }},
        {BlendMode::Min, [](double x, double y) { return std::min(x, y); }},
        {BlendMode::Max, [](double x, double y) { return std::max(x, y); }},
    };
    for (const auto& [mode, f] : cases) {
        BlendParameters p;
        p.mode = mode;
        p.opacity = 0.8;
        const BlendSource blend("b", &base, &over, nullptr, p);
        const ImageTile& tile = *evaluator.tile(blend, TileKey{}).value();
        for (int c = 0; c < 3; ++c) {
            const double expected = b[c] + (f(b[c], o[c]) - b[c]) * w;
            EXPECT_NEAR(tile.at(5, 1, c), expected, 1e-6) << static_cast<int>(mode) << " " << c;
        }
        EXPECT_NEAR(tile.at(5, 1, 3), 1.0, 1e-6);
    }
}

TEST(BlendSource, MaskWeightsPerTexel) {
    const ConstantSource base("base", 100.0), over("over", 300.0);
    const FunctionMask mask(
        7, [](double latitude, double) { return std::clamp(0.5 + latitude, 0.0, 1.0); });
    BlendParameters p;
    p.opacity = 0.5;
    const BlendSource blend("b", &base, &over, &mask, p);
    EXPECT_EQ(blend.output(), PortType::Elevation);
    TileEvaluator evaluator(TileFormat{16, 2});
    TileKey key;
    key.level = 2;
    key.x = 3;
    key.y = 1;
    const ImageTile& tile = *evaluator.tile(blend, key).value();
    for (int iy = 0; iy < 16; iy += 5) {
        const double m = std::clamp(0.5 + tile.texelLatitude(iy), 0.0, 1.0);
        EXPECT_NEAR(tile.at(4, iy, 0), 100.0 + 200.0 * 0.5 * m, 1e-3);
    }
}

TEST(BlendSource, ElevationModes) {
    const ConstantSource base("base", 100.0), over("over", 40.0);
    TileEvaluator evaluator(TileFormat{8, 2});
    const std::pair<BlendMode, double> cases[] = {{BlendMode::Normal, 40.0},
                                                  {BlendMode::Add, 140.0},
                                                  {BlendMode::Min, 40.0},
                                                  {BlendMode::Max, 100.0}};
    for (const auto& [mode, expected] : cases) {
        BlendParameters p;
        p.mode = mode;
        const BlendSource blend("b", &base, &over, nullptr, p);
        EXPECT_NEAR(evaluator.tile(blend, TileKey{}).value()->at(2, 2, 0), expected, 1e-4);
    }
}

// A local DEM (UTM zone 25S, 64 x 64 pixels of 90 m, heights 10..40 m) merged into a
// constant 200 m relief.
std::filesystem::path localDem() {
    static const std::filesystem::path path = [] {
        GdalDatasetPool::registerDrivers();
        auto folder = std::filesystem::temp_directory_path() /
                      ("sylva_blend_test_" + std::to_string(::getpid()));
        std::filesystem::create_directories(folder);
        const auto file = folder / "dem.tif";
        GDALDatasetH ds =
            GDALCreate(GDALGetDriverByName("GTiff"), file.c_str(), 64, 64, 1, GDT_Float32, nullptr);
        double gt[6] = {288776.25, 90.0, 0.0, 9120760.75, 0.0, -90.0};
        GDALSetGeoTransform(ds, gt);
        OGRSpatialReferenceH srs = OSRNewSpatialReference(nullptr);
        OSRImportFromEPSG(srs, 32725);
        GDALSetSpatialRef(ds, srs);
        OSRDestroySpatialReference(srs);
        std::vector<float> data(64 * 64);
        for (int r = 0; r < 64; ++r) {
            for (int c = 0; c < 64; ++c) {
                data[std::size_t(r) * 64 + c] = 10.0f + 0.25f * c + 0.25f * r;
            }
        }
        EXPECT_EQ(GDALRasterIO(GDALGetRasterBand(ds, 1), GF_Write, 0, 0, 64, 64, data.data(), 64,
                               64, GDT_Float32, 0, 0),
                  CE_None);
        GDALClose(ds);
        return file;
    }();
    return path;
}

TileKey tileAt(double latitudeDegrees, double longitudeDegrees, int level) {
    TileKey key;
    key.level = level;
    key.x = static_cast<int>(std::floor((longitudeDegrees + 180.0) / 360.0 * key.columns()));
    key.y = static_cast<int>(std::floor((90.0 - latitudeDegrees) / 180.0 * key.rows()));
    return key;
}

// Largest height step between neighbouring texels along the rows of a tile that are
// more than 2 km from the DEM's north and south edges (latitudes -7.970 .. -7.980).
double largestStep(const ImageTile& tile) {
    double step = 0.0;
    for (int iy = 0; iy < tile.size(); ++iy) {
        const double lat = tile.texelLatitude(iy) / kDegree;
        if (lat > -7.970 || lat < -7.980) {
            continue;
        }
        for (int ix = 0; ix + 1 < tile.size(); ++ix) {
            step = std::max(step, double(std::abs(tile.at(ix + 1, iy, 0) - tile.at(ix, iy, 0))));
        }
    }
    return step;
}

TEST(BlendSource, FeatherMergesALocalDemWithoutAStep) {
    RasterParameters rp;
    rp.file = localDem();
    auto dem = RasterSource::open("dem", rp);
    ASSERT_FALSE(dem->openError()) << dem->openError()->message;
    const ConstantSource relief("relief", 200.0);
    BlendParameters hard;
    const BlendSource sharp("sharp", &relief, dem.get(), nullptr, hard);
    BlendParameters soft;
    soft.feather = 1000.0;
    const BlendSource feathered("soft", &relief, dem.get(), nullptr, soft);
    EXPECT_EQ(BlendSource::coverageOf(*dem), dem->coverage());
    EXPECT_EQ(BlendSource::coverageOf(feathered),
              nullptr);  // a blend passes on its base's coverage

    TileEvaluator evaluator(TileFormat{64, 2});
    // Level 12 texels are ~76 m; this tile holds the DEM's west edge (lon -34.916).
    const TileKey key = tileAt(-7.975, -34.916, 12);
    const ImageTile& a = *evaluator.tile(sharp, key).value();
    const ImageTile& b = *evaluator.tile(feathered, key).value();
    // Without feather the edge is a cliff of ~180 m within a texel or two ...
    EXPECT_GT(largestStep(a), 60.0);
    // ... with a 1 km feather the fade spans at least 0.6 km (8 texels), so no step
    // exceeds smoothstep's steepest slope, 1.5 x 180 m / 8 = 34 m.
    EXPECT_LT(largestStep(b), 35.0);
    // Far outside: the relief; well inside: the DEM itself.
    const ImageTile& demTile = *evaluator.tile(*dem, key).value();
    const ImageTile& coverage = *evaluator.tile(*dem->coverage(), key).value();
    int inside = 0, outside = 0;
    for (int iy = 0; iy < 64; ++iy) {
        for (int ix = 0; ix < 64; ++ix) {
            const double lon = b.texelLongitude(ix) / kDegree, lat = b.texelLatitude(iy) / kDegree;
            if (coverage.at(ix, iy, 0) == 0.0f) {
                EXPECT_FLOAT_EQ(b.at(ix, iy, 0), 200.0f);
                ++outside;
            } else if (lon > -34.916 + 0.02 && lat < -7.970 && lat > -7.980) {  // > 2 km inside
                EXPECT_NEAR(b.at(ix, iy, 0), demTile.at(ix, iy, 0), 1e-3);
                ++inside;
            }
        }
    }
    EXPECT_GT(inside, 20);
    EXPECT_GT(outside, 100);

    // Seamless across tiles: the east border column of this tile equals the first
    // interior column of the next tile.
    TileKey east = key;
    east.x += 1;
    const ImageTile& next = *evaluator.tile(feathered, east).value();
    for (int iy = 0; iy < 64; ++iy) {
        EXPECT_NEAR(b.at(64, iy, 0), next.at(0, iy, 0), 1e-3);
    }
}

// A constant elevation that counts the tiles it produces.
class CountingElevation final : public Source {
public:
    CountingElevation(std::string name, float height)
        : Source(std::move(name), "counting", PortType::Elevation, 1), height_(height) {
        setParameterHash(std::uint64_t(height * 1000.0f) + 17);
    }
    Result<TilePointer> produce(const TileKey& key, TileProvider& provider) const override {
        ++produced;
        const TileFormat& format = provider.format();
        auto tile = std::make_shared<ImageTile>(key, format.size, format.border, 1);
        for (int iy = -format.border; iy < format.size + format.border; ++iy) {
            for (int ix = -format.border; ix < format.size + format.border; ++ix) {
                tile->at(ix, iy, 0) = height_;
            }
        }
        return TilePointer(std::move(tile));
    }
    mutable int produced = 0;

private:
    float height_;
};

TEST(BlendSource, ReadsAnInputOnlyWhereItHasWeight) {
    const FunctionMask everywhere(21, [](double, double) { return 1.0; });
    const FunctionMask nowhere(22, [](double, double) { return 0.0; });
    const FunctionMask half(23, [](double, double) { return 0.5; });
    struct Case {
        const Source* mask;
        BlendMode mode;
        int baseReads, overReads;
        float expected;
    };
    const Case cases[] = {{&everywhere, BlendMode::Normal, 0, 1, 40.0f},  // replaced: no base
                          {&everywhere, BlendMode::Max, 1, 1, 100.0f},    // max needs the base
                          {&nowhere, BlendMode::Normal, 1, 0, 100.0f},    // no weight: no over
                          {&half, BlendMode::Normal, 1, 1, 70.0f}};
    for (const Case& c : cases) {
        const CountingElevation base("base", 100.0f), over("over", 40.0f);
        BlendParameters p;
        p.mode = c.mode;
        const BlendSource blend("b", &base, &over, c.mask, p);
        TileEvaluator evaluator(TileFormat{8, 2});
        const ImageTile& tile = *evaluator.tile(blend, TileKey{}).value();
        EXPECT_EQ(base.produced, c.baseReads) << static_cast<int>(c.mode);
        EXPECT_EQ(over.produced, c.overReads) << static_cast<int>(c.mode);
        EXPECT_FLOAT_EQ(tile.at(3, 4, 0), c.expected);
        EXPECT_FLOAT_EQ(tile.at(-2, 9, 0), c.expected);  // the border too
    }
}

TEST(BlendSource, AReliefUnderTheInsideOfADemIsNeverProduced) {
    RasterParameters rp;
    rp.file = localDem();
    auto dem = RasterSource::open("dem", rp);
    ASSERT_FALSE(dem->openError()) << dem->openError()->message;
    const CountingElevation relief("relief", 200.0f);
    BlendParameters soft;
    soft.feather = 1000.0;
    const BlendSource feathered("soft", &relief, dem.get(), nullptr, soft);
    TileEvaluator evaluator(TileFormat{16, 2});
    // Level 16 texels are ~4.8 m: a 77 m tile in the middle of the 5.8 km DEM.
    const TileKey inside = tileAt(-7.975, -34.89, 16);
    const ImageTile& merged = *evaluator.tile(feathered, inside).value();
    EXPECT_EQ(relief.produced, 0);
    const ImageTile& demTile = *evaluator.tile(*dem, inside).value();
    for (int iy = -2; iy < 18; ++iy) {
        for (int ix = -2; ix < 18; ++ix) {
            ASSERT_EQ(merged.at(ix, iy, 0), demTile.at(ix, iy, 0)) << ix << " " << iy;
        }
    }
    // Across the DEM's west edge the relief is read (and blended in).
    evaluator.tile(feathered, tileAt(-7.975, -34.916, 12)).value();
    EXPECT_EQ(relief.produced, 1);
}

}  // namespace
}  // namespace sylva
