#include "sylva/core/sources/raster/MaskSource.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <numbers>

#include <gdal.h>
#include <ogr_srs_api.h>

#include "sylva/core/scheduler/TileEvaluator.h"
#include "sylva/core/sources/raster/ConstantSource.h"
#include "sylva/core/sources/raster/RasterSource.h"

namespace sylva {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

// An image given as a function of (latitude, longitude) in radians.
class FunctionImage final : public Source {
public:
    FunctionImage(std::string name, std::uint64_t tag, std::function<glm::vec4(double, double)> f)
        : Source(std::move(name), "function", PortType::Image, 4), f_(std::move(f)) {
        setParameterHash(tag);
    }
    Result<TilePointer> produce(const TileKey& key, TileProvider& provider) const override {
        const TileFormat& format = provider.format();
        auto tile = std::make_shared<ImageTile>(key, format.size, format.border, 4);
        for (int iy = -format.border; iy < format.size + format.border; ++iy) {
            for (int ix = -format.border; ix < format.size + format.border; ++ix) {
                const glm::vec4 v = f_(tile->texelLatitude(iy), tile->texelLongitude(ix));
                for (int c = 0; c < 4; ++c) {
                    tile->at(ix, iy, c) = v[c];
                }
            }
        }
        return TilePointer(std::move(tile));
    }

private:
    std::function<glm::vec4(double, double)> f_;
};

TEST(MaskSource, NdviExpressionEqualsDirectComputation) {
    auto nirOf = [](double lat, double lon) {
        return 0.3 + 0.2 * std::sin(40 * lat) * std::cos(30 * lon);
    };
    auto redOf = [](double lat, double lon) { return 0.2 + 0.15 * std::cos(25 * lat + 10 * lon); };
    const FunctionImage nir("nir", 1, [&](double lat, double lon) {
        return glm::vec4(float(nirOf(lat, lon)), 0, 0, 1);
    });
    const FunctionImage red("red", 2, [&](double lat, double lon) {
        return glm::vec4(float(redOf(lat, lon)), 0, 0,
                         lon > 0.5 ? 0.0f : 1.0f);  // no data east of 0.5 rad
    });
    MaskParameters p;
    p.expression = "(nir - red) / (nir + red) > 0.35";
    Result<std::unique_ptr<MaskSource>> mask = MaskSource::make("forest", {&nir, &red}, p);
    ASSERT_TRUE(mask) << mask.error().message;
    TileEvaluator evaluator(TileFormat{32, 2});
    TileKey key;
    key.level = 2;
    key.x = 4;
    key.y = 1;
    const ImageTile& tile = *evaluator.tile(**mask, key).value();
    int ones = 0, zeros = 0;
    for (int iy = -2; iy < 34; ++iy) {
        for (int ix = -2; ix < 34; ++ix) {
            const double lat = tile.texelLatitude(iy), lon = tile.texelLongitude(ix);
            const double n = float(nirOf(lat, lon)), r = float(redOf(lat, lon));
            const float expected = (lon > 0.5) ? 0.0f : ((n - r) / (n + r) > 0.35 ? 1.0f : 0.0f);
            EXPECT_EQ(tile.at(ix, iy, 0), expected) << ix << "," << iy;
            (expected > 0 ? ones : zeros)++;
        }
    }
    EXPECT_GT(ones, 20);
    EXPECT_GT(zeros, 20);
}

TEST(MaskSource, ExpressionErrorsAreReported) {
    const ConstantSource grey("grey", glm::vec4(0.5f));
    MaskParameters p;
    p.expression = "grey.b5 > 1";
    Result<std::unique_ptr<MaskSource>> mask = MaskSource::make("m", {&grey}, p);
    ASSERT_FALSE(mask);
    EXPECT_EQ(mask.error().message, "unknown name 'grey.b5' at column 1");
    p.expression = "grey.g * 2 + b3 - grey";
    EXPECT_TRUE(MaskSource::make("m", {&grey}, p));
}

TEST(MaskSource, NearestClassColour) {
    // West half reddish, east half greenish (linear RGB).
    const FunctionImage image("img", 3, [](double, double lon) {
        return lon < 0.0 ? glm::vec4(0.6f, 0.2f, 0.1f, 1) : glm::vec4(0.15f, 0.5f, 0.2f, 1);
    });
    MaskParameters p;
    p.classes = {glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1)};
    p.select = 1;  // green
    Result<std::unique_ptr<MaskSource>> mask = MaskSource::make("m", {&image}, p);
    ASSERT_TRUE(mask);
    TileEvaluator evaluator(TileFormat{16, 2});
    TileKey key;  // level 0, x 0: west hemisphere
    const ImageTile& west = *evaluator.tile(**mask, key).value();
    key.x = 1;
    const ImageTile& east = *evaluator.tile(**mask, key).value();
    EXPECT_EQ(west.at(8, 8, 0), 0.0f);
    EXPECT_EQ(east.at(8, 8, 0), 1.0f);
}

// Single-texel specks vanish with an opening, single-texel holes with a closing, and a
// feathered edge changes by no more than 1 / (2 r + 1) per texel (a tent of radius 2r).
TEST(MaskSource, MorphologyAndFeather) {
    TileKey key;
    key.level = 10;
    key.x = 700;
    key.y = 300;
    const int size = 64;
    const double texel = (key.east() - key.west()) / size;
    const double west = key.west();
    auto column = [=](double lon) { return static_cast<int>(std::floor((lon - west) / texel)); };
    // Specks: columns 10 and 40 (one texel wide) in a mask that is 1 east of column 32.
    const FunctionImage image("img", 4, [=](double, double lon) {
        const int c = column(lon);
        float v = c >= 32 ? 1.0f : 0.0f;
        if (c == 10)
            v = 1.0f;
        if (c == 40)
            v = 0.0f;
        return glm::vec4(v, v, v, 1.0f);
    });
    const double texelMetres = std::numbers::pi * 6371008.8 / (size * std::ldexp(1.0, key.level));
    TileEvaluator evaluator(TileFormat{size, 2});
    {
        MaskParameters p;
        p.open = 1.0 * texelMetres;
        const ImageTile& t = *evaluator.tile(**MaskSource::make("o", {&image}, p), key).value();
        EXPECT_EQ(t.at(10, 20, 0), 0.0f);  // speck removed
        EXPECT_EQ(t.at(40, 20, 0), 0.0f);  // hole kept
        EXPECT_EQ(t.at(50, 20, 0), 1.0f);
    }
    {
        MaskParameters p;
        p.close = 1.0 * texelMetres;
        const ImageTile& t = *evaluator.tile(**MaskSource::make("c", {&image}, p), key).value();
        EXPECT_EQ(t.at(10, 20, 0), 1.0f);  // speck kept
        EXPECT_EQ(t.at(40, 20, 0), 1.0f);  // hole filled
        EXPECT_EQ(t.at(5, 20, 0), 0.0f);
    }
    {
        MaskParameters p;
        p.open = 1.0 * texelMetres;
        p.close = 1.0 * texelMetres;
        p.feather = 4.0 * texelMetres;
        const ImageTile& t = *evaluator.tile(**MaskSource::make("f", {&image}, p), key).value();
        EXPECT_EQ(MaskSource::radiusTexels(p.feather, size, key.level), 4);
        double step = 0.0;
        for (int ix = -2; ix + 1 < size + 2; ++ix) {
            step = std::max(step, double(std::abs(t.at(ix + 1, 20, 0) - t.at(ix, 20, 0))));
        }
        EXPECT_LE(step, 1.0 / 9.0 + 1e-5);
        EXPECT_NEAR(t.at(2, 20, 0), 0.0, 1e-6);
        EXPECT_NEAR(t.at(60, 20, 0), 1.0, 1e-6);
        EXPECT_NEAR(t.at(32, 20, 0) + t.at(31, 20, 0), 1.0, 1e-5);  // symmetric about the edge
    }
}

// NDVI of the real Landsat scene (scripts/fetch-samples) equals the direct computation
// on GDAL's pixels, with nearest resampling at texels finer than the 28.5 m pixels.
TEST(MaskSource, LandsatNdviEqualsDirectComputation) {
    const std::filesystem::path path =
        std::filesystem::path(SYLVA_TEST_DATA_DIR) / "../data/olinda/L7_ETMs.tif";
    if (!std::filesystem::exists(path)) {
        GTEST_SKIP() << "sample data absent (" << path << "); run scripts/fetch-samples";
    }
    auto band = [&](int number) {
        RasterParameters p;
        p.file = path;
        p.kind = RasterKind::Image;
        p.bands = {number};
        p.srgb = false;
        p.resampling = Resampling::Nearest;
        return RasterSource::open(number == 4 ? "nir" : "red", p);
    };
    auto nir = band(4), red = band(3);
    ASSERT_FALSE(nir->openError()) << nir->openError()->message;
    MaskParameters p;
    p.expression = "(nir - red) / (nir + red) > 0.35";
    auto mask = MaskSource::make("forest", {nir.get(), red.get()}, p);
    ASSERT_TRUE(mask);
    // Level 14 with 64-texel tiles: ~19 m texels.
    TileKey key;
    key.level = 14;
    key.x = static_cast<int>(std::floor((-34.88 + 180.0) / 360.0 * key.columns()));
    key.y = static_cast<int>(std::floor((90.0 + 7.99) / 180.0 * key.rows()));
    TileEvaluator evaluator(TileFormat{64, 2});
    const ImageTile& tile = *evaluator.tile(**mask, key).value();

    GDALDatasetH dataset = GDALOpen(path.c_str(), GA_ReadOnly);
    double gt[6], inv[6];
    GDALGetGeoTransform(dataset, gt);
    ASSERT_TRUE(GDALInvGeoTransform(gt, inv));
    const int width = GDALGetRasterXSize(dataset), height = GDALGetRasterYSize(dataset);
    std::vector<float> b3(std::size_t(width) * height), b4(b3.size());
    ASSERT_EQ(GDALRasterIO(GDALGetRasterBand(dataset, 3), GF_Read, 0, 0, width, height, b3.data(),
                           width, height, GDT_Float32, 0, 0),
              CE_None);
    ASSERT_EQ(GDALRasterIO(GDALGetRasterBand(dataset, 4), GF_Read, 0, 0, width, height, b4.data(),
                           width, height, GDT_Float32, 0, 0),
              CE_None);
    OGRSpatialReferenceH wgs = OSRNewSpatialReference(nullptr);
    OSRImportFromEPSG(wgs, 4326);
    OSRSetAxisMappingStrategy(wgs, OAMS_TRADITIONAL_GIS_ORDER);
    OGRSpatialReferenceH utm = OSRNewSpatialReference(GDALGetProjectionRef(dataset));
    OSRSetAxisMappingStrategy(utm, OAMS_TRADITIONAL_GIS_ORDER);
    OGRCoordinateTransformationH ct = OCTNewCoordinateTransformation(wgs, utm);
    int compared = 0, forest = 0;
    for (int iy = 0; iy < 64; ++iy) {
        for (int ix = 0; ix < 64; ++ix) {
            double x = tile.texelLongitude(ix) / kDegree, y = tile.texelLatitude(iy) / kDegree;
            OCTTransform(ct, 1, &x, &y, nullptr);
            const int col = static_cast<int>(std::floor(inv[0] + x * inv[1] + y * inv[2]));
            const int row = static_cast<int>(std::floor(inv[3] + x * inv[4] + y * inv[5]));
            if (col < 0 || row < 0 || col >= width || row >= height) {
                continue;
            }
            const double n = b4[std::size_t(row) * width + col],
                         r = b3[std::size_t(row) * width + col];
            const double ndvi = n + r > 0 ? (n - r) / (n + r) : 0.0;
            if (std::abs(ndvi - 0.35) < 1e-6) {
                continue;  // exactly on the threshold: rounding decides
            }
            EXPECT_EQ(tile.at(ix, iy, 0), ndvi > 0.35 ? 1.0f : 0.0f) << ix << "," << iy;
            forest += ndvi > 0.35;
            ++compared;
        }
    }
    OCTDestroyCoordinateTransformation(ct);
    OSRDestroySpatialReference(wgs);
    OSRDestroySpatialReference(utm);
    GDALClose(dataset);
    EXPECT_GT(compared, 1000);
    EXPECT_GT(forest, 0);
}

}  // namespace
}  // namespace sylva
