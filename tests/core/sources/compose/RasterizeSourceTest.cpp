#include "sylva/core/sources/compose/RasterizeSource.h"

#include <gtest/gtest.h>

#include <GeographicLib/Ellipsoid.hpp>
#include <GeographicLib/Geodesic.hpp>
#include <GeographicLib/PolygonArea.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>

#include <unistd.h>
#include <numbers>

#include "sylva/core/geo/Geodesy.h"
#include "sylva/core/scheduler/TileEvaluator.h"
#include "sylva/core/sources/vector/CoverageRasterizer.h"

namespace sylva {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

// Area of texel rows on WGS84 by GeographicLib's authalic latitude (independent of
// CoverageRasterizer::quadrangleArea).
double referenceQuadArea(double latitude1, double latitude2, double longitudeSpan) {
    const GeographicLib::Ellipsoid& e = GeographicLib::Ellipsoid::WGS84();
    const double xi1 = e.AuthalicLatitude(latitude1 / kDegree) * kDegree;
    const double xi2 = e.AuthalicLatitude(latitude2 / kDegree) * kDegree;
    return e.Area() / (4.0 * std::numbers::pi) * longitudeSpan *
           std::abs(std::sin(xi2) - std::sin(xi1));
}

// A polygon approximating a geodesic circle (many short edges, so straight edges in
// longitude/latitude and geodesic edges enclose the same area to ~1e-7).
Feature circle(double latitude, double longitude, double radius, int vertices) {
    Feature f;
    f.kind = GeometryKind::Polygon;
    f.parts = {{}};
    for (int i = 0; i <= vertices; ++i) {
        double lat = 0.0, lon = 0.0;
        Geodesy::destination(latitude, longitude,
                             2.0 * std::numbers::pi * (i % vertices) / vertices, radius, lat, lon);
        f.parts[0].emplace_back(lon, lat);
    }
    return f;
}

double geodesicArea(const Feature& f) {
    GeographicLib::PolygonArea polygon(GeographicLib::Geodesic::WGS84());
    for (std::size_t i = 0; i + 1 < f.parts[0].size(); ++i) {
        polygon.AddPoint(f.parts[0][i].y / kDegree, f.parts[0][i].x / kDegree);
    }
    double perimeter = 0.0, area = 0.0;
    polygon.Compute(false, true, perimeter, area);
    return std::abs(area);
}

// Every interior texel of the tiles of `level` over `bounds`: sum of coverage x area.
double rasterizedArea(const FeatureCollection& features, int level, const GeographicBounds& bounds,
                      int* fractional) {
    const int size = 256, border = 2;
    double area = 0.0;
    TileKey probe;
    probe.level = level;
    const int columns = probe.columns(), rows = probe.rows();
    const int x0 =
        int(std::floor((bounds.west + std::numbers::pi) / (2 * std::numbers::pi) * columns));
    const int x1 =
        int(std::floor((bounds.east + std::numbers::pi) / (2 * std::numbers::pi) * columns));
    const int y0 = int(std::floor((std::numbers::pi / 2 - bounds.north) / std::numbers::pi * rows));
    const int y1 = int(std::floor((std::numbers::pi / 2 - bounds.south) / std::numbers::pi * rows));
    std::vector<float> coverage;
    for (int y = y0; y <= y1; ++y) {
        for (int x = x0; x <= x1; ++x) {
            TileKey key = probe;
            key.x = x;
            key.y = y;
            const CoverageRasterizer rasterizer(key, size, border);
            for (const FeatureHit& hit :
                 features.query({key.west(), key.south(), key.east(), key.north()})) {
                rasterizer.fillPolygon(hit.feature->parts, hit.longitudeShift, coverage);
                for (int iy = 0; iy < size; ++iy) {
                    const double north = key.north() - iy * (key.north() - key.south()) / size;
                    const double texelArea =
                        referenceQuadArea(north - (key.north() - key.south()) / size, north,
                                          (key.east() - key.west()) / size);
                    for (int ix = 0; ix < size; ++ix) {
                        const float c =
                            coverage[std::size_t(iy + border) * rasterizer.width() + ix + border];
                        area += c * texelArea;
                        if (c > 0.02f && c < 0.98f) {
                            ++*fractional;
                        }
                    }
                }
            }
        }
    }
    return area;
}

TEST(RasterizeSource, PolygonAreaMatchesGeodesicAreaAtManyLatitudes) {
    for (const double latitude : {0.3, 23.0, 45.0, 61.0, 75.0, -52.0, -80.0}) {
        const Feature f = circle(latitude * kDegree, 10.0 * kDegree, 2500.0, 720);
        auto features = FeatureCollection::fromFeatures({}, {f});
        int fractional = 0;
        const double area =
            rasterizedArea(*features, 12, features->features()[0].bounds, &fractional);
        const double expected = geodesicArea(f);
        EXPECT_NEAR(area / expected, 1.0, 0.01) << "latitude " << latitude;
        // The exact-coverage rasterizer is far better than the 1 % asked for.
        EXPECT_NEAR(area / expected, 1.0, 0.001) << "latitude " << latitude;
        EXPECT_GT(fractional, 100) << "edges are anti-aliased";
    }
}

TEST(RasterizeSource, QuadrangleAreaMatchesGeographicLib) {
    for (const double lat : {-89.0, -45.0, 0.0, 30.0, 60.0, 88.0}) {
        const double a =
            CoverageRasterizer::quadrangleArea(lat * kDegree, (lat + 0.5) * kDegree, 0.7 * kDegree);
        EXPECT_NEAR(a / referenceQuadArea(lat * kDegree, (lat + 0.5) * kDegree, 0.7 * kDegree), 1.0,
                    1e-10);
    }
}

// FeatureSource reads files, so rasterize is driven through a real GeoJSON file.
std::filesystem::path writeGeoJson(const std::string& name, const std::string& text) {
    const auto folder =
        std::filesystem::temp_directory_path() / ("sylva-rasterize-" + std::to_string(::getpid()));
    std::filesystem::create_directories(folder);
    const auto path = folder / name;
    std::ofstream(path) << text;
    return path;
}

TEST(RasterizeSource, LineWidthInMetresAtAnyLatitude) {
    for (const double latitude : {0.0, 45.0, 70.0}) {
        // A meridian segment and a parallel segment, 40 m wide, through the tile centre.
        TileKey key;
        key.level = 14;
        key.x = int(std::floor((0.005 * kDegree + std::numbers::pi) / (2 * std::numbers::pi) *
                               key.columns()));
        key.y = int(std::floor((std::numbers::pi / 2 - latitude * kDegree) / std::numbers::pi *
                               key.rows()));
        const double lat = 0.5 * (key.north() + key.south()), lon = 0.5 * (key.west() + key.east());
        Feature meridian, parallel;
        meridian.kind = parallel.kind = GeometryKind::Line;
        meridian.parts = {{{lon, lat - 0.01 * kDegree}, {lon, lat + 0.01 * kDegree}}};
        parallel.parts = {{{lon - 0.01 * kDegree, lat}, {lon + 0.01 * kDegree, lat}}};
        auto features = FeatureCollection::fromFeatures({}, {meridian, parallel});
        const CoverageRasterizer rasterizer(key, 256, 2);
        std::vector<float> coverage(std::size_t(rasterizer.width()) * rasterizer.width(), 0.0f);
        rasterizer.strokeLines(features->features()[0].parts, 0.0, 40.0, coverage);
        // Across the meridian line: sum along a row x east metres per texel.
        const int row = 130;
        double sum = 0.0;
        int partial = 0;
        for (int gx = 0; gx < rasterizer.width(); ++gx) {
            const float c = coverage[std::size_t(row) * rasterizer.width() + gx];
            sum += c;
            partial += (c > 0.01f && c < 0.99f);
        }
        const glm::dvec2 metres = rasterizer.metresPerTexel(row + 0.5);
        // Independent metric: GeographicLib distance of one texel eastwards.
        const glm::dvec2 a = rasterizer.toLonLat({0.0, row + 0.5}),
                         b = rasterizer.toLonLat({1.0, row + 0.5});
        const double texelEast = Geodesy::distance(a.y, a.x, b.y, b.x);
        EXPECT_NEAR(metres.x / texelEast, 1.0, 1e-6);
        EXPECT_NEAR(sum * texelEast, 40.0, 0.4) << "latitude " << latitude;
        EXPECT_GT(partial, 0);
        std::fill(coverage.begin(), coverage.end(), 0.0f);
        rasterizer.strokeLines(features->features()[1].parts, 0.0, 40.0, coverage);
        const glm::dvec2 line = rasterizer.toGrid({lon, lat});
        sum = 0.0;
        const int column = int(line.x) + 20;
        for (int gy = 0; gy < rasterizer.width(); ++gy) {
            sum += coverage[std::size_t(gy) * rasterizer.width() + column];
        }
        const glm::dvec2 c = rasterizer.toLonLat({column + 0.5, line.y}),
                         d = rasterizer.toLonLat({column + 0.5, line.y + 1.0});
        EXPECT_NEAR(sum * Geodesy::distance(c.y, c.x, d.y, d.x), 40.0, 0.4)
            << "latitude " << latitude;
    }
}

// Issue 16: a 150 m border seen from afar must not flood coarse levels. Its coverage
// summed over a coarse tile (× texel area) is the line's metric area, whatever
// minimum_texels; at a fine level it is drawn at full opacity.
TEST(RasterizeSource, WidenedLinesKeepTheirMetricAreaOnCoarseTiles) {
    const auto path = writeGeoJson(
        "border.geojson",
        R"({"type":"FeatureCollection","features":[)"
        R"({"type":"Feature","properties":{},"geometry":{"type":"LineString","coordinates":[[8.5,45.5],[8.5,46.5]]}}]})");
    FeatureSource features("border", path, {});
    const double length =
        Geodesy::distance(45.5 * kDegree, 8.5 * kDegree, 46.5 * kDegree, 8.5 * kDegree);
    const int size = 256, border = 2;
    TileEvaluator evaluator(TileFormat{size, border});
    const auto tileKey = [](int level) {
        TileKey key;
        key.level = level;
        key.x = int(std::floor((8.5 * kDegree + std::numbers::pi) / (2 * std::numbers::pi) *
                               key.columns()));
        key.y = int(
            std::floor((std::numbers::pi / 2 - 46.0 * kDegree) / std::numbers::pi * key.rows()));
        return key;
    };
    for (const double minimumTexels : {0.0, 1.5, 4.0}) {
        RasterizeParameters parameters;
        parameters.image = false;
        parameters.lineWidth = 150.0;
        parameters.minimumTexels = minimumTexels;
        RasterizeSource source("border.mask", &features, nullptr, parameters);
        // Level 6: texels of about 1.2 km; the whole line lies inside the tile.
        const TileKey key = tileKey(6);
        Result<TilePointer> tile = evaluator.tile(source, key);
        ASSERT_TRUE(tile) << tile.error().message;
        double area = 0.0;
        float largest = 0.0f;
        for (int iy = 0; iy < size; ++iy) {
            const double north = key.north() - iy * (key.north() - key.south()) / size;
            const double texelArea = referenceQuadArea(north - (key.north() - key.south()) / size,
                                                       north, (key.east() - key.west()) / size);
            for (int ix = 0; ix < size; ++ix) {
                area += tile.value()->at(ix, iy, 0) * texelArea;
                largest = std::max(largest, tile.value()->at(ix, iy, 0));
            }
        }
        // Ink = opacity × drawn area = 150 m / drawn × (drawn × length + π drawn² / 4): the
        // metric area plus the round caps' share (3.5 % at 4 texels).
        const double middle = 0.5 * (key.north() + key.south());
        const double texelHeight = (key.north() - key.south()) / size;
        const double texelMetres = Geodesy::distance(middle - texelHeight / 2, 8.5 * kDegree,
                                                     middle + texelHeight / 2, 8.5 * kDegree);
        const double drawn = std::max(150.0, minimumTexels * texelMetres);
        const double ink = 150.0 * (length + std::numbers::pi * drawn / 4);
        EXPECT_NEAR(area / ink, 1.0, 0.03) << "minimum_texels " << minimumTexels;
        EXPECT_NEAR(area / (length * 150.0), 1.0, 0.04) << "minimum_texels " << minimumTexels;
        // Faded, not flooded: no texel is more covered than 150 m of its ~1.2 km.
        EXPECT_LT(largest, 0.2f) << "minimum_texels " << minimumTexels;
        // Level 16: 150 m is many texels wide, drawn opaque.
        Result<TilePointer> fine = evaluator.tile(source, tileKey(16));
        ASSERT_TRUE(fine) << fine.error().message;
        float fineLargest = 0.0f;
        for (float c : fine.value()->texels()) {
            fineLargest = std::max(fineLargest, c);
        }
        EXPECT_FLOAT_EQ(fineLargest, 1.0f) << "minimum_texels " << minimumTexels;
    }
}

TEST(RasterizeSource, ColoursFromAttributesAndErrors) {
    const auto path = writeGeoJson(
        "landuse.geojson",
        R"({"type":"FeatureCollection","features":[)"
        R"({"type":"Feature","properties":{"use":"forest","hex":"#ff0000"},"geometry":{"type":"Polygon","coordinates":[[[0,0],[10,0],[10,10],[0,10],[0,0]]]}},)"
        R"({"type":"Feature","properties":{"use":"marsh","hex":"bogus"},"geometry":{"type":"Polygon","coordinates":[[[-10,-10],[-1,-10],[-1,-1],[-10,-1],[-10,-10]]]}}]})");
    FeatureSource features("landuse", path, {});
    TileEvaluator evaluator(TileFormat{64, 2});
    TileKey key;  // level 0, the eastern hemisphere... use level 2 around (0, 0)
    key.level = 2;
    key.x = 4;
    key.y = 1;
    RasterizeParameters byMap;
    byMap.colorAttribute = "use";
    byMap.colors = {{"forest", {0.0f, 0.5f, 0.0f}}};
    RasterizeSource mapped("mapped", &features, nullptr, byMap);
    Result<TilePointer> missing = evaluator.tile(mapped, key);
    ASSERT_FALSE(missing);
    EXPECT_EQ(missing.error().message,
              "source 'mapped', tile L2/k0/x4/y1: " + path.string() +
                  ": feature 1: attribute 'use': value 'marsh' is not in colors");

    RasterizeParameters byHex;
    byHex.colorAttribute = "hex";
    RasterizeSource hex("hex", &features, nullptr, byHex);
    Result<TilePointer> bad = evaluator.tile(hex, key);
    ASSERT_FALSE(bad);
    EXPECT_EQ(bad.error().message,
              "source 'hex', tile L2/k0/x4/y1: " + path.string() +
                  ": feature 1: attribute 'hex': 'bogus' is not a hex colour such as #1a8c3f");

    byMap.colors.push_back({"marsh", {0.0f, 0.0f, 1.0f}});
    RasterizeSource good("good", &features, nullptr, byMap);
    Result<TilePointer> tile = evaluator.tile(good, key);
    ASSERT_TRUE(tile) << tile.error().message;
    const ImageTile& t = *tile.value();
    // Texel at (5 deg, 5 deg) is forest green, (-5, -5) is marsh blue, (30, 30) transparent.
    auto texelAt = [&](double lonDeg, double latDeg) {
        const int ix = int((lonDeg * kDegree - key.west()) / t.texelWidth());
        const int iy = int((key.north() - latDeg * kDegree) / t.texelHeight());
        return glm::vec4(t.at(ix, iy, 0), t.at(ix, iy, 1), t.at(ix, iy, 2), t.at(ix, iy, 3));
    };
    EXPECT_EQ(texelAt(5, 5), glm::vec4(0.0f, 0.5f, 0.0f, 1.0f));
    EXPECT_EQ(texelAt(30, 30).w, 0.0f);
    EXPECT_TRUE(RasterizeSource::parseHexColor("#fff").has_value());
    EXPECT_FALSE(RasterizeSource::parseHexColor("#ggg000").has_value());
}

TEST(RasterizeSource, AntimeridianPolygonCoversBothSides) {
    Feature f;
    f.kind = GeometryKind::Polygon;
    f.parts = {{{179.5 * kDegree, -0.5 * kDegree},
                {-179.5 * kDegree, -0.5 * kDegree},
                {-179.5 * kDegree, 0.5 * kDegree},
                {179.5 * kDegree, 0.5 * kDegree},
                {179.5 * kDegree, -0.5 * kDegree}}};
    auto features = FeatureCollection::fromFeatures({}, {f});
    int fractional = 0;
    const double east = rasterizedArea(
        *features, 6, {179.0 * kDegree, -0.6 * kDegree, 179.99 * kDegree, 0.6 * kDegree},
        &fractional);
    const double west = rasterizedArea(
        *features, 6, {-179.99 * kDegree, -0.6 * kDegree, -179.0 * kDegree, 0.6 * kDegree},
        &fractional);
    const double expected = referenceQuadArea(-0.5 * kDegree, 0.5 * kDegree, 1.0 * kDegree);
    EXPECT_NEAR((east + west) / expected, 1.0, 1e-6);
    EXPECT_NEAR(east / west, 1.0, 1e-6);
}

}  // namespace
}  // namespace sylva
