// Buildings extruded from footprints: heights against the terrain (flat and sloped), roof
// shapes against their analytic apex heights, the flat roof's area against GeographicLib's
// geodesic area of the footprint, courtyards, tiling, and the located errors of bad input.
#include "sylva/core/sources/objects/BuildingsSource.h"

#include <gtest/gtest.h>

#include <GeographicLib/Geodesic.hpp>
#include <GeographicLib/PolygonArea.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>

#include <unistd.h>

#include "sylva/core/base/Hash.h"
#include "sylva/core/geo/Ellipsoid.h"
#include "sylva/core/scheduler/TileEvaluator.h"
#include "sylva/core/sources/raster/ConstantSource.h"

namespace sylva {
namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
constexpr double kLatitude = -7.96, kLongitude = -34.90;  // degrees

std::filesystem::path folder() {
    const auto path =
        std::filesystem::temp_directory_path() / ("sylva-buildings-" + std::to_string(::getpid()));
    std::filesystem::create_directories(path);
    return path;
}

// A ring of (east, north) metres about the test point as GeoJSON coordinates.
std::string ring(const std::vector<std::pair<double, double>>& metres) {
    const double east = Ellipsoid::primeVerticalRadius(kLatitude * kDegree) *
                        std::cos(kLatitude * kDegree) * kDegree;
    const double north = Ellipsoid::meridionalRadius(kLatitude * kDegree) * kDegree;
    std::string out = "[";
    for (std::size_t i = 0; i <= metres.size(); ++i) {
        const auto& [x, y] = metres[i % metres.size()];
        char text[96];
        std::snprintf(text, sizeof text, "%s[%.10f,%.10f]", i ? "," : "", kLongitude + x / east,
                      kLatitude + y / north);
        out += text;
    }
    return out + "]";
}

std::filesystem::path writeGeoJson(const std::string& name, const std::string& features) {
    const auto path = folder() / name;
    std::ofstream(path) << R"({"type":"FeatureCollection","features":[)" << features << "]}";
    return path;
}

std::string polygon(int id, const std::string& properties, const std::string& rings) {
    return R"({"type":"Feature","id":)" + std::to_string(id) + R"(,"properties":{)" + properties +
           R"(},"geometry":{"type":"Polygon","coordinates":[)" + rings + "]}}";
}

const std::vector<std::pair<double, double>> kRectangle{{-20, -15}, {20, -15}, {20, 15}, {-20, 15}};

// An elevation that rises 10 % towards the east (a plane in longitude).
class SlopeSource final : public Source {
public:
    SlopeSource() : Source("slope", "test", PortType::Elevation, 1) {
        setParameterHash(ContentHash().add(std::string_view("slope-v1")).value());
    }
    static double height(double longitude) {
        const double east =
            Ellipsoid::primeVerticalRadius(kLatitude * kDegree) * std::cos(kLatitude * kDegree);
        return 100.0 + 0.1 * (longitude - kLongitude * kDegree) * east;
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

struct Built {
    std::shared_ptr<const MeshTile> tile;
    double lowest = std::numeric_limits<double>::infinity();
    double highest = -std::numeric_limits<double>::infinity();
    double roofArea = 0.0;  // upward faces projected on the local horizontal plane
};

Result<Built> build(const std::filesystem::path& file, const Source& elevation,
                    BuildingsParameters parameters) {
    FeatureSource features("footprints", file, {});
    BuildingsSource buildings("houses", &features, &elevation, std::move(parameters));
    Result<std::vector<TileKey>> keys = buildings.tileKeys();
    if (!keys) {
        return keys.error();
    }
    TileEvaluator evaluator(TileFormat{64, 2});
    Built built;
    for (const TileKey& key : keys.value()) {
        Result<std::shared_ptr<const MeshTile>> tile = buildings.tile(key, evaluator);
        if (!tile) {
            return tile.error();
        }
        built.tile = tile.value();
        const MeshGeometry& g = tile.value()->geometry;
        for (const MeshVertex& v : g.vertices) {
            const double h =
                Ellipsoid::toGeodetic(tile.value()->origin + glm::dvec3(v.position)).height;
            built.lowest = std::min(built.lowest, h);
            built.highest = std::max(built.highest, h);
        }
        const glm::dvec3 up = Ellipsoid::surfaceNormal(kLatitude * kDegree, kLongitude * kDegree);
        for (std::size_t i = 0; i < g.indices.size(); i += 3) {
            const glm::dvec3 a(g.vertices[g.indices[i]].position);
            const glm::dvec3 b(g.vertices[g.indices[i + 1]].position);
            const glm::dvec3 c(g.vertices[g.indices[i + 2]].position);
            const double projected = 0.5 * glm::dot(glm::cross(b - a, c - a), up);
            if (projected > 1e-6) {
                built.roofArea += projected;
            }
        }
    }
    return built;
}

double geodesicArea(const std::vector<std::pair<double, double>>& metres) {
    const double east = Ellipsoid::primeVerticalRadius(kLatitude * kDegree) *
                        std::cos(kLatitude * kDegree) * kDegree;
    const double north = Ellipsoid::meridionalRadius(kLatitude * kDegree) * kDegree;
    GeographicLib::PolygonArea area(GeographicLib::Geodesic::WGS84());
    for (const auto& [x, y] : metres) {
        area.AddPoint(kLatitude + y / north, kLongitude + x / east);
    }
    double perimeter = 0, result = 0;
    area.Compute(false, true, perimeter, result);
    return result;
}

TEST(BuildingsSource, FlatRoofStandsOnTheTerrainAndCoversTheGeodesicArea) {
    const auto file = writeGeoJson("flat.geojson", polygon(1, R"("h":"12.5")", ring(kRectangle)));
    const ConstantSource ground("ground", 100.0);
    BuildingsParameters p;
    p.heightAttribute = "h";
    Result<Built> built = build(file, ground, p);
    ASSERT_TRUE(built) << built.error().message;
    EXPECT_NEAR(built.value().highest, 112.5, 1e-3);
    EXPECT_NEAR(built.value().lowest, 99.5, 1e-3);  // the walls' skirt below the ground
    const double area = geodesicArea(kRectangle);
    EXPECT_NEAR(built.value().roofArea, area, 1e-4 * area);
    EXPECT_EQ(built.value().tile->featureCount, 1u);
}

TEST(BuildingsSource, CourtyardIsLeftOpen) {
    const std::vector<std::pair<double, double>> hole{{-5, -5}, {-5, 5}, {5, 5}, {5, -5}};
    const auto file = writeGeoJson("courtyard.geojson",
                                   polygon(1, R"("f":3)", ring(kRectangle) + "," + ring(hole)));
    const ConstantSource ground("ground", 0.0);
    BuildingsParameters p;
    p.floorsAttribute = "f";
    p.storeyHeight = 3.0;
    Result<Built> built = build(file, ground, p);
    ASSERT_TRUE(built) << built.error().message;
    EXPECT_NEAR(built.value().highest, 9.0, 1e-3);
    // The hole's ring runs clockwise: GeographicLib gives its area negative.
    const double area = geodesicArea(kRectangle) - std::abs(geodesicArea(hole));
    EXPECT_NEAR(built.value().roofArea, area, 1e-4 * area);
}

TEST(BuildingsSource, BaseIsTheLowestOrMeanGroundOnASlope) {
    const auto file = writeGeoJson("slope.geojson", polygon(1, "", ring(kRectangle)));
    const SlopeSource slope;
    BuildingsParameters p;
    p.height = 10.0;
    // Ground from 98 m (west wall, 20 m west) to 102 m (east wall).
    Result<Built> lowest = build(file, slope, p);
    ASSERT_TRUE(lowest) << lowest.error().message;
    EXPECT_NEAR(lowest.value().highest, 98.0 + 10.0, 0.02);
    EXPECT_NEAR(lowest.value().lowest, 98.0 - 0.5, 0.02);
    p.meanBase = true;
    Result<Built> mean = build(file, slope, p);
    ASSERT_TRUE(mean) << mean.error().message;
    EXPECT_NEAR(mean.value().highest, 100.0 + 10.0, 0.05);
    EXPECT_NEAR(mean.value().lowest, 98.0 - 0.5, 0.02);  // walls still reach the lowest point
}

TEST(BuildingsSource, SlopedRoofsRiseByThePitchOverHalfTheWidth) {
    const ConstantSource ground("ground", 0.0);
    // 40 m × 30 m: the ridge runs east-west, half the width is 15 m.
    for (const char* roof : {"gable", "hip", "pyramid"}) {
        const auto file =
            writeGeoJson(std::string(roof) + ".geojson",
                         polygon(1, std::string(R"("roof":")") + roof + "\"", ring(kRectangle)));
        BuildingsParameters p;
        p.height = 6.0;
        p.roofAttribute = "roof";
        p.pitch = 30 * kDegree;
        Result<Built> built = build(file, ground, p);
        ASSERT_TRUE(built) << roof << ": " << built.error().message;
        EXPECT_NEAR(built.value().highest, 6.0 + 15.0 * std::tan(30 * kDegree), 2e-3) << roof;
        const double area = geodesicArea(kRectangle);
        EXPECT_NEAR(built.value().roofArea, area, 1e-3 * area) << roof;
    }
}

Status buildError(const std::string& name, const std::string& features,
                  BuildingsParameters parameters = {}) {
    const auto file = writeGeoJson(name, features);
    const ConstantSource ground("ground", 0.0);
    Result<Built> built = build(file, ground, std::move(parameters));
    if (built) {
        return Status::success();
    }
    return built.error();
}

TEST(BuildingsSource, BadFootprintsAreLocatedErrors) {
    const std::string point =
        R"({"type":"Feature","id":4,"properties":{},"geometry":{"type":"Point","coordinates":[-34.9,-7.96]}})";
    Status status = buildError("point.geojson", point);
    ASSERT_FALSE(status);
    EXPECT_NE(status.error().message.find("point.geojson: feature 4: a building footprint must be "
                                          "a polygon, not a point"),
              std::string::npos)
        << status.error().message;

    BuildingsParameters height;
    height.heightAttribute = "h";
    status = buildError("nan.geojson", polygon(7, R"("h":"tall")", ring(kRectangle)), height);
    ASSERT_FALSE(status);
    EXPECT_NE(status.error().message.find("nan.geojson: feature 7: attribute 'h' is not a number: "
                                          "'tall'"),
              std::string::npos)
        << status.error().message;

    status = buildError("unset.geojson",
                        polygon(8, R"("h":null,"k":1)", ring(kRectangle)) + "," +
                            polygon(9, R"("h":"3","k":1)", ring(kRectangle)),
                        height);
    ASSERT_FALSE(status);
    EXPECT_NE(status.error().message.find("unset.geojson: feature 8: attribute 'h' is missing"),
              std::string::npos)
        << status.error().message;

    BuildingsParameters absent;
    absent.heightAttribute = "height";
    status = buildError("absent.geojson", polygon(1, R"("h":"3")", ring(kRectangle)), absent);
    ASSERT_FALSE(status);
    EXPECT_NE(status.error().message.find("absent.geojson: no attribute 'height' (attributes: h)"),
              std::string::npos)
        << status.error().message;
}

TEST(BuildingsSource, SelfIntersectingFootprintIsALocatedError) {
    const std::vector<std::pair<double, double>> bowtie{{-10, -10}, {10, 10}, {10, -10}, {-10, 10}};
    const Status status = buildError("bowtie.geojson", polygon(5, "", ring(bowtie)));
    ASSERT_FALSE(status);
    EXPECT_NE(status.error().message.find("bowtie.geojson"), std::string::npos)
        << status.error().message;
    EXPECT_NE(status.error().message.find("feature 5"), std::string::npos)
        << status.error().message;
    EXPECT_NE(status.error().message.find("intersect"), std::string::npos)
        << status.error().message;
}

}  // namespace
}  // namespace sylva
