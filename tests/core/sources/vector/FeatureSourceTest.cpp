#include "sylva/core/sources/vector/FeatureSource.h"

#include <gtest/gtest.h>

#include <GeographicLib/UTMUPS.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <random>
#include <thread>

#include <unistd.h>

namespace sylva {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
namespace fs = std::filesystem;

fs::path writeFile(const std::string& name, const std::string& text) {
    const fs::path folder =
        fs::temp_directory_path() / ("sylva-features-" + std::to_string(::getpid()));
    fs::create_directories(folder);
    const fs::path path = folder / name;
    std::ofstream(path) << text;
    return path;
}

std::string polygonFeature(const std::string& name, const std::string& ring) {
    return R"({"type":"Feature","properties":{"name":")" + name + R"(","height":12.5},)" +
           R"("geometry":{"type":"Polygon","coordinates":[)" + ring + "]}}";
}

std::string collection(const std::vector<std::string>& features) {
    std::string out = R"({"type":"FeatureCollection","features":[)";
    for (std::size_t i = 0; i < features.size(); ++i) {
        out += (i ? "," : "") + features[i];
    }
    return out + "]}";
}

TEST(FeatureSource, LoadsGeoJsonWithAttributesAndFilter) {
    const fs::path path = writeFile(
        "two.geojson", collection({polygonFeature("a", "[[0,0],[1,0],[1,1],[0,1],[0,0]]"),
                                   polygonFeature("b", "[[10,10],[11,10],[11,11],[10,10]]")}));
    Result<std::shared_ptr<const FeatureCollection>> all =
        FeatureCollection::load(path.string(), {});
    ASSERT_TRUE(all) << all.error().message;
    ASSERT_EQ(all.value()->features().size(), 2u);
    const Feature& a = all.value()->features()[0];
    EXPECT_EQ(a.kind, GeometryKind::Polygon);
    EXPECT_EQ(a.attributes[*all.value()->field("name")], "a");
    EXPECT_NEAR(a.bounds.east, 1.0 * kDegree, 1e-15);
    EXPECT_NEAR(a.bounds.north, 1.0 * kDegree, 1e-15);
    FeatureLoadOptions options;
    options.where = "name = 'b'";
    Result<std::shared_ptr<const FeatureCollection>> filtered =
        FeatureCollection::load(path.string(), options);
    ASSERT_TRUE(filtered) << filtered.error().message;
    ASSERT_EQ(filtered.value()->features().size(), 1u);
    EXPECT_EQ(filtered.value()->features()[0].attributes[0], "b");
}

TEST(FeatureSource, ReprojectsFromUtmLikeGeographicLib) {
    // A point in UTM zone 25S (EPSG:32725), written as an old-style GeoJSON with a CRS.
    const double easting = 295000.0, northing = 9115000.0;
    const fs::path path = writeFile(
        "utm.geojson",
        R"({"type":"FeatureCollection","crs":{"type":"name","properties":{"name":"urn:ogc:def:crs:EPSG::32725"}},)"
        R"("features":[{"type":"Feature","properties":{},"geometry":{"type":"Point","coordinates":[295000,9115000]}}]})");
    Result<std::shared_ptr<const FeatureCollection>> loaded =
        FeatureCollection::load(path.string(), {});
    ASSERT_TRUE(loaded) << loaded.error().message;
    double latitude = 0.0, longitude = 0.0;
    GeographicLib::UTMUPS::Reverse(25, false, easting, northing, latitude, longitude);
    const glm::dvec2 p = loaded.value()->features()[0].parts[0][0];
    EXPECT_NEAR(p.x, longitude * kDegree, 1e-9);  // ~6 mm
    EXPECT_NEAR(p.y, latitude * kDegree, 1e-9);
}

TEST(FeatureSource, ErrorsNameFileLayerFieldAndFeature) {
    const fs::path good =
        writeFile("good.geojson", collection({polygonFeature("a", "[[0,0],[1,0],[1,1],[0,0]]")}));
    Result<std::shared_ptr<const FeatureCollection>> missing =
        FeatureCollection::load((good.parent_path() / "nothing.gpkg").string(), {});
    ASSERT_FALSE(missing);
    EXPECT_EQ(
        missing.error().message.rfind(
            (good.parent_path() / "nothing.gpkg").string() + ": cannot open as vector data (", 0),
        0u)
        << missing.error().message;

    FeatureLoadOptions layer;
    layer.layer = "roads";
    Result<std::shared_ptr<const FeatureCollection>> noLayer =
        FeatureCollection::load(good.string(), layer);
    ASSERT_FALSE(noLayer);
    EXPECT_EQ(noLayer.error().message, good.string() + ": no layer 'roads' (layers: good)");

    FeatureLoadOptions where;
    where.where = "nosuch = 1";
    Result<std::shared_ptr<const FeatureCollection>> noField =
        FeatureCollection::load(good.string(), where);
    ASSERT_FALSE(noField);
    EXPECT_EQ(
        noField.error().message,
        good.string() +
            ": layer 'good': where 'nosuch = 1': \"nosuch\" not recognised as an available field.");

    const fs::path open =
        writeFile("open.geojson", collection({polygonFeature("o", "[[0,0],[1,0],[1,1],[0,1]]")}));
    Result<std::shared_ptr<const FeatureCollection>> unclosed =
        FeatureCollection::load(open.string(), {});
    ASSERT_FALSE(unclosed);
    EXPECT_EQ(unclosed.error().message,
              open.string() + ": layer 'open': feature 0: unclosed polygon ring");

    const fs::path bowtie = writeFile(
        "bowtie.geojson", collection({polygonFeature("ok", "[[0,0],[1,0],[1,1],[0,0]]"),
                                      polygonFeature("x", "[[0,0],[1,1],[1,0],[0,1],[0,0]]")}));
    Result<std::shared_ptr<const FeatureCollection>> invalid =
        FeatureCollection::load(bowtie.string(), {});
    ASSERT_FALSE(invalid);
    EXPECT_EQ(invalid.error().message.rfind(
                  bowtie.string() + ": layer 'bowtie': feature 1: invalid geometry", 0),
              0u)
        << invalid.error().message;
    FeatureLoadOptions skip;
    skip.invalid = FeatureLoadOptions::Invalid::Skip;
    Result<std::shared_ptr<const FeatureCollection>> skipped =
        FeatureCollection::load(bowtie.string(), skip);
    ASSERT_TRUE(skipped);
    EXPECT_EQ(skipped.value()->features().size(), 1u);
    FeatureLoadOptions repair;
    repair.invalid = FeatureLoadOptions::Invalid::Repair;
    Result<std::shared_ptr<const FeatureCollection>> repaired =
        FeatureCollection::load(bowtie.string(), repair);
    ASSERT_TRUE(repaired) << repaired.error().message;
    EXPECT_EQ(repaired.value()->features().size(), 2u);

    const fs::path empty = writeFile(
        "empty.geojson",
        R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{},"geometry":null}]})");
    Result<std::shared_ptr<const FeatureCollection>> none =
        FeatureCollection::load(empty.string(), {});
    ASSERT_FALSE(none);
    EXPECT_EQ(none.error().message, empty.string() + ": layer 'empty': feature 0: empty geometry");
}

TEST(FeatureSource, AntimeridianAndPolarRings) {
    Feature crossing;
    crossing.kind = GeometryKind::Polygon;
    crossing.parts = {{{179 * kDegree, 0},
                       {-179 * kDegree, 0},
                       {-179 * kDegree, kDegree},
                       {179 * kDegree, kDegree},
                       {179 * kDegree, 0}}};
    Feature polar;  // a ring once around the south pole, like Antarctica's coast
    polar.kind = GeometryKind::Polygon;
    polar.parts = {{}};
    for (int lon = -180; lon <= 180; lon += 30) {
        polar.parts[0].emplace_back(lon * kDegree, -70 * kDegree);
    }
    auto features = FeatureCollection::fromFeatures({}, {crossing, polar});
    const Feature& c = features->features()[0];
    EXPECT_NEAR(c.bounds.east - c.bounds.west, 2 * kDegree, 1e-12);  // continuous, not 358 degrees
    const GeographicBounds westOfLine{-std::numbers::pi, 0.1 * kDegree, -179.5 * kDegree,
                                      0.2 * kDegree};
    std::vector<FeatureHit> hits = features->query(westOfLine);
    ASSERT_EQ(hits.size(), 1u);  // the crossing polygon, shifted by -2 pi; not the polar one
    EXPECT_EQ(hits[0].feature, &c);
    EXPECT_NEAR(hits[0].longitudeShift, -2 * std::numbers::pi, 1e-15);
    EXPECT_GE(c.bounds.east + hits[0].longitudeShift, westOfLine.west);
    const Feature& p = features->features()[1];
    EXPECT_NEAR(p.bounds.south, -std::numbers::pi / 2, 1e-15);  // closed along the pole
    EXPECT_NEAR(p.bounds.north, -70 * kDegree, 1e-15);
    // Positive orientation (counter-clockwise in lon/lat) for an outer ring.
    double area = 0.0;
    for (std::size_t i = 0; i + 1 < p.parts[0].size(); ++i) {
        area += p.parts[0][i].x * p.parts[0][i + 1].y - p.parts[0][i + 1].x * p.parts[0][i].y;
    }
    EXPECT_GT(area, 0.0);
}

TEST(FeatureSource, RTreeQueryEqualsBruteForce) {
    std::mt19937 random(7);
    std::uniform_real_distribution<double> lon(-3.0, 3.0), lat(-1.4, 1.4), size(0.0, 0.05);
    std::vector<Feature> features;
    for (int i = 0; i < 3000; ++i) {
        Feature f;
        f.kind = GeometryKind::Line;
        const glm::dvec2 a(lon(random), lat(random));
        f.parts = {{a, a + glm::dvec2(size(random), size(random))}};
        features.push_back(f);
    }
    auto collection = FeatureCollection::fromFeatures({}, features);
    for (int q = 0; q < 200; ++q) {
        const double west = lon(random), south = lat(random);
        const GeographicBounds window{west, south, west + 0.2, south + 0.1};
        std::vector<FeatureHit> hits = collection->query(window);
        std::vector<const Feature*> expected;
        for (const Feature& f : collection->features()) {
            if (f.bounds.intersects(window)) {
                expected.push_back(&f);
            }
        }
        ASSERT_EQ(hits.size(), expected.size());
        for (std::size_t i = 0; i < hits.size(); ++i) {
            EXPECT_EQ(hits[i].feature, expected[i]);
        }
    }
}

TEST(FeatureSource, LoadsOncePerContentAcrossThreads) {
    const fs::path path =
        writeFile("shared.geojson", collection({polygonFeature("a", "[[0,0],[1,0],[1,1],[0,0]]")}));
    FeatureSource first("a", path, {});
    FeatureSource second("b", path, {});
    EXPECT_EQ(first.contentHash(), second.contentHash());
    std::vector<const FeatureCollection*> seen(8, nullptr);
    std::vector<std::thread> threads;
    for (int i = 0; i < 8; ++i) {
        threads.emplace_back([&, i] {
            seen[std::size_t(i)] = ((i % 2) ? first : second).collection().value().get();
        });
    }
    for (std::thread& t : threads) {
        t.join();
    }
    for (const FeatureCollection* c : seen) {
        EXPECT_EQ(c, seen[0]);
    }
    FeatureSource broken("c", path.parent_path() / "absent.shp", {});
    Result<std::shared_ptr<const FeatureCollection>> error1 = broken.collection();
    Result<std::shared_ptr<const FeatureCollection>> error2 = broken.collection();
    ASSERT_FALSE(error1);
    EXPECT_EQ(error1.error().message, error2.error().message);
}

TEST(FeatureSource, LoadsWorldCountries) {
    const fs::path world = fs::path(SYLVA_TEST_DATA_DIR) / "../data/world/world.gpkg";
    if (!fs::exists(world)) {
        GTEST_SKIP() << "sample data absent: " << world;
    }
    FeatureLoadOptions options;
    Result<std::shared_ptr<const FeatureCollection>> loaded =
        FeatureCollection::load(world.string(), options);
    ASSERT_TRUE(loaded) << loaded.error().message;
    EXPECT_EQ(loaded.value()->features().size(), 177u);
    // Olinda (Brazil) lies in exactly one country polygon's bounds set that includes Brazil.
    const double lon = -34.86 * kDegree, lat = -8.0 * kDegree;
    bool brazil = false;
    for (const FeatureHit& hit : loaded.value()->query({lon, lat, lon, lat})) {
        for (const std::string& value : hit.feature->attributes) {
            brazil = brazil || value == "Brazil";
        }
    }
    EXPECT_TRUE(brazil);
}

}  // namespace
}  // namespace sylva
