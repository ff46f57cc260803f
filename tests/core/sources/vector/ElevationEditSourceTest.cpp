#include "sylva/core/sources/vector/ElevationEditSource.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include <unistd.h>

#include "sylva/core/geo/Geodesy.h"
#include "sylva/core/scheduler/TileEvaluator.h"
#include "sylva/core/sources/compose/BlendSource.h"
#include "sylva/core/sources/raster/ConstantSource.h"
#include "sylva/core/sources/raster/RasterSource.h"

namespace sylva {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

// A square polygon of `halfDegrees` about (lonDeg, latDeg) with a numeric attribute.
std::filesystem::path squareFile(const std::string& name, double lonDeg, double latDeg,
                                 double halfDegrees, const std::string& level = "50") {
    const auto folder =
        std::filesystem::temp_directory_path() / ("sylva-edit-" + std::to_string(::getpid()));
    std::filesystem::create_directories(folder);
    const auto path = folder / name;
    auto c = [](double v) { return std::to_string(v); };
    const double w = lonDeg - halfDegrees, e = lonDeg + halfDegrees, s = latDeg - halfDegrees,
                 n = latDeg + halfDegrees;
    std::ofstream(path)
        << R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{"crest":")"
        << level << R"("},"geometry":{"type":"Polygon","coordinates":[[[)" << c(w) << "," << c(s)
        << "],[" << c(e) << "," << c(s) << "],[" << c(e) << "," << c(n) << "],[" << c(w) << ","
        << c(n) << "],[" << c(w) << "," << c(s) << "]]]}}]}";
    return path;
}

struct Fixture {
    TileKey key;
    Fixture(double lonDeg, double latDeg, int level) {
        key.level = level;
        key.x = int(std::floor((lonDeg * kDegree + std::numbers::pi) / (2 * std::numbers::pi) *
                               key.columns()));
        key.y = int(
            std::floor((std::numbers::pi / 2 - latDeg * kDegree) / std::numbers::pi * key.rows()));
    }
};

double smoothstep(double t) {
    t = std::clamp(t, 0.0, 1.0);
    return t * t * (3 - 2 * t);
}

TEST(ElevationEditSource, FlattenWithFeatherFollowsTheAnalyticProfile) {
    for (const double latitude : {0.0, 52.0, -71.0}) {
        Fixture f(10.0, latitude, 12);
        const double lonC = 0.5 * (f.key.west() + f.key.east()) / kDegree;
        const double latC = 0.5 * (f.key.north() + f.key.south()) / kDegree;
        const auto path = squareFile("dam.geojson", lonC, latC, 0.005);
        const ConstantSource ground("ground", 100.0);
        FeatureSource features("dam", path, {});
        ElevationEditParameters p;
        p.mode = ElevationEditParameters::Mode::Flatten;
        p.height = 50.0;
        p.feather = 300.0;
        ElevationEditSource edit("edit", &ground, &features, p);
        TileEvaluator evaluator(TileFormat{256, 2});
        Result<TilePointer> tile = evaluator.tile(edit, f.key);
        ASSERT_TRUE(tile) << tile.error().message;
        const ImageTile& t = *tile.value();
        int checked = 0;
        for (int iy = 0; iy < 256; iy += 3) {
            for (int ix = 0; ix < 256; ix += 3) {
                const double lat = t.texelLatitude(iy), lon = t.texelLongitude(ix);
                const bool inside = std::abs(lat / kDegree - latC) < 0.005 &&
                                    std::abs(lon / kDegree - lonC) < 0.005;
                double expected = 50.0;
                if (!inside) {
                    // Distance to the square by GeographicLib: to the nearest edge point
                    // (east/west edges are meridians, north/south edges parallels).
                    const double edgeLat =
                        std::clamp(lat / kDegree, latC - 0.005, latC + 0.005) * kDegree;
                    const double edgeLon =
                        std::clamp(lon / kDegree, lonC - 0.005, lonC + 0.005) * kDegree;
                    const double d = Geodesy::distance(lat, lon, edgeLat, edgeLon);
                    expected = 100.0 - 50.0 * smoothstep(1.0 - d / 300.0);
                }
                // Within a few cm: the reference uses geodesics, the source the local metric.
                ASSERT_NEAR(t.at(ix, iy, 0), expected, 0.1)
                    << "latitude " << latitude << " texel " << ix << "," << iy;
                ++checked;
            }
        }
        EXPECT_GT(checked, 1000);
    }
}

TEST(ElevationEditSource, RaiseLowerAndAttributeHeights) {
    Fixture f(-34.9, -8.0, 13);
    const double lonC = 0.5 * (f.key.west() + f.key.east()) / kDegree;
    const double latC = 0.5 * (f.key.north() + f.key.south()) / kDegree;
    const auto path = squareFile("pit.geojson", lonC, latC, 0.002, "37.5");
    const ConstantSource ground("ground", 20.0);
    FeatureSource features("pit", path, {});
    TileEvaluator evaluator(TileFormat{64, 2});
    auto centre = [&](const Source& source) {
        const ImageTile& t = *evaluator.tile(source, f.key).value();
        return t.at(32, 32, 0);
    };
    ElevationEditParameters p;
    p.mode = ElevationEditParameters::Mode::Raise;
    p.amount = 7.0;
    EXPECT_FLOAT_EQ(centre(ElevationEditSource("raise", &ground, &features, p)), 27.0f);
    p.mode = ElevationEditParameters::Mode::Lower;
    EXPECT_FLOAT_EQ(centre(ElevationEditSource("lower", &ground, &features, p)), 13.0f);
    p.mode = ElevationEditParameters::Mode::Flatten;
    p.heightAttribute = "crest";
    EXPECT_FLOAT_EQ(centre(ElevationEditSource("crest", &ground, &features, p)), 37.5f);
    p.heightAttribute = "missing";
    ElevationEditSource missing("missing", &ground, &features, p);
    Result<TilePointer> error = evaluator.tile(missing, f.key);
    ASSERT_FALSE(error);
    EXPECT_EQ(error.error().message, "source 'missing', tile " + f.key.toString() + ": " +
                                         path.string() +
                                         ": no attribute 'missing' (for source 'missing')");
    const auto bad = squareFile("bad.geojson", lonC, latC, 0.002, "high");
    FeatureSource badFeatures("bad", bad, {});
    p.heightAttribute = "crest";
    ElevationEditSource notNumber("nan", &ground, &badFeatures, p);
    Result<TilePointer> error2 = evaluator.tile(notNumber, f.key);
    ASSERT_FALSE(error2);
    EXPECT_EQ(error2.error().message, "source 'nan', tile " + f.key.toString() + ": " +
                                          bad.string() +
                                          ": feature 0: attribute 'crest' is not a number: 'high'");
}

TEST(ElevationEditSource, SlopeIsAPlaneThroughTheCentroid) {
    Fixture f(7.0, 46.0, 12);
    const double lonC = 0.5 * (f.key.west() + f.key.east()) / kDegree;
    const double latC = 0.5 * (f.key.north() + f.key.south()) / kDegree;
    const auto path = squareFile("cliff.geojson", lonC, latC, 0.01);
    const ConstantSource ground("ground", 500.0);
    FeatureSource features("cliff", path, {});
    ElevationEditParameters p;
    p.mode = ElevationEditParameters::Mode::Slope;
    p.height = 400.0;
    p.gradient = 0.25;
    p.direction = 90.0 * kDegree;  // rising eastwards
    ElevationEditSource edit("slope", &ground, &features, p);
    TileEvaluator evaluator(TileFormat{256, 2});
    const ImageTile& t = *evaluator.tile(edit, f.key).value();
    int checked = 0;
    for (int iy = 0; iy < 256; iy += 5) {
        for (int ix = 0; ix < 256; ix += 5) {
            const double lat = t.texelLatitude(iy), lon = t.texelLongitude(ix);
            if (std::abs(lat / kDegree - latC) > 0.0099 ||
                std::abs(lon / kDegree - lonC) > 0.0099) {
                continue;
            }
            // Signed east distance from the centroid's meridian along the parallel.
            const double east =
                Geodesy::distance(lat, lonC * kDegree, lat, lon) * (lon > lonC * kDegree ? 1 : -1);
            ASSERT_NEAR(t.at(ix, iy, 0), 400.0 + 0.25 * east, 0.05) << ix << "," << iy;
            ++checked;
        }
    }
    EXPECT_GT(checked, 500);
}

TEST(ElevationEditSource, PassesItsInputsCoverageToBlend) {
    RasterParameters raster;
    raster.file = squareFile("unused.geojson", 0, 0, 1).parent_path() / "dem.tif";
    raster.kind = RasterKind::Elevation;
    const std::unique_ptr<RasterSource> dem = RasterSource::open("dem", raster);
    FeatureSource features("dam", squareFile("dam2.geojson", 0, 0, 0.01), {});
    ElevationEditSource edit("edit", dem.get(), &features, {});
    ASSERT_NE(dem->coverage(), nullptr);
    EXPECT_EQ(BlendSource::coverageOf(edit), dem->coverage());
    const ConstantSource flat("flat", 0.0);
    ElevationEditSource onConstant("edit2", &flat, &features, {});
    EXPECT_EQ(BlendSource::coverageOf(onConstant), nullptr);
}

}  // namespace
}  // namespace sylva
