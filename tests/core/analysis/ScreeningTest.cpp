// The screened ZTV against the geometric shadow of a wall: flat ground, a target of
// height T at column t, a wall of height W covering columns [a, b] over every row. An
// eye h above the ground at column c > b sees the top exactly when the sight line
// clears the wall's near edge (the grid line through the centres of column b; between
// b and b + 1 the surface ramps down, lower than the line whenever the edge is):
//     hidden  ⇔  h + (T − h)(c − b)/(c − t) < W,
// the same ratio for every row (distances along the ray scale with columns). The wall
// comes three ways, each must give that shadow: a surface made by hand, a building
// footprint (GeoJSON polygon with a `height`, rasterized), a canopy height raster
// (GeoTIFF). Cells inside the wall hold no observer (NaN fraction). Bad screen files
// fail with the path and the reason.
#include "sylva/core/analysis/ScreeningSurface.h"

#include <cpl_conv.h>
#include <gdal.h>
#include <gtest/gtest.h>
#include <ogr_srs_api.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <vector>

#include "sylva/core/analysis/Viewshed.h"

namespace sylva {
namespace {

namespace fs = std::filesystem;

constexpr int kWidth = 160, kHeight = 40;
constexpr double kCell = 5.0;
constexpr int kTargetCol = 20, kTargetRow = 20, kWallFirst = 60, kWallLast = 61;
constexpr double kTargetHeight = 30.0, kWallHeight = 10.0, kEye = 2.0;

std::string utm25s() {
    OGRSpatialReferenceH srs = OSRNewSpatialReference(nullptr);
    OSRImportFromEPSG(srs, 32725);
    char* wkt = nullptr;
    OSRExportToWkt(srs, &wkt);
    std::string out = wkt;
    CPLFree(wkt);
    OSRDestroySpatialReference(srs);
    return out;
}

ElevationGrid flatGround() {
    ElevationGrid grid;
    grid.geometry = {290000.0, 9120000.0, kCell, kCell, kWidth, kHeight};
    grid.heights.assign(std::size_t(kWidth) * kHeight, 12.0f);
    grid.crsWkt = utm25s();
    return grid;
}

ViewshedOptions flatOptions() {
    ViewshedOptions options;
    options.curvature = false;
    options.observerHeight = kEye;
    return options;
}

bool inShadow(int col) {
    if (col <= kWallLast)
        return false;
    const double line =
        kEye + (kTargetHeight - kEye) * double(col - kWallLast) / double(col - kTargetCol);
    return line < kWallHeight;
}

// Every cell against the analytic shadow; returns the number of hidden cells.
int expectWallShadow(const ElevationGrid& ground, const ElevationGrid& surface,
                     ViewshedMethod method, const std::string& tag) {
    const GridGeometry& g = ground.geometry;
    const ViewshedTarget target{g.centreX(kTargetCol), g.centreY(kTargetRow), kTargetHeight};
    ViewshedOptions options = flatOptions();
    options.method = method;
    auto result = computeViewshed(ground, surface, std::span(&target, 1), options);
    EXPECT_TRUE(result.ok()) << result.error().message;
    if (!result)
        return 0;
    int hidden = 0, wrong = 0;
    for (int r = 0; r < kHeight; ++r)
        for (int c = 0; c < kWidth; ++c) {
            const std::size_t i = std::size_t(r) * kWidth + std::size_t(c);
            if (c >= kWallFirst && c <= kWallLast) {
                wrong += std::isnan(result->fraction[i]) && result->visible[i] == 0 ? 0 : 1;
                continue;
            }
            const bool expectVisible = !inShadow(c);
            hidden += expectVisible ? 0 : 1;
            wrong += (result->visible[i] == 1) == expectVisible ? 0 : 1;
        }
    EXPECT_EQ(wrong, 0) << tag;
    return hidden;
}

int expectWallShadowFree(const ElevationGrid& ground) {
    const GridGeometry& g = ground.geometry;
    const ViewshedTarget target{g.centreX(kTargetCol), g.centreY(kTargetRow), kTargetHeight};
    auto result = computeViewshed(ground, std::span(&target, 1), flatOptions());
    return result ? int(result->cells() - result->visibleCells()) : -1;
}

ElevationGrid wallSurface(const ElevationGrid& ground) {
    ElevationGrid surface = ground;
    for (int r = 0; r < kHeight; ++r)
        for (int c = kWallFirst; c <= kWallLast; ++c)
            surface.heights[std::size_t(r) * kWidth + std::size_t(c)] += float(kWallHeight);
    return surface;
}

TEST(Screening, WallHidesExactlyItsGeometricShadow) {
    const ElevationGrid ground = flatGround();
    const ElevationGrid surface = wallSurface(ground);
    const int hidden = expectWallShadow(ground, surface, ViewshedMethod::Sweep, "sweep");
    EXPECT_EQ(expectWallShadow(ground, surface, ViewshedMethod::Exact, "exact"), hidden);
    // The shadow ends where h + (T − h)(c − b)/(c − t) = W: c = ((T − h)b − (W − h)t)/(T − W).
    const double end = (kWallLast * (kTargetHeight - kEye) - kTargetCol * (kWallHeight - kEye)) /
                       (kTargetHeight - kWallHeight);
    EXPECT_EQ(hidden, kHeight * (int(std::ceil(end)) - kWallLast - 1));
    EXPECT_GT(hidden, 0);
    // Without the screen everything is visible on flat ground.
    EXPECT_EQ(expectWallShadowFree(ground), 0);
}

fs::path scratch(const std::string& name) {
    const fs::path dir = fs::path(SYLVA_TEST_OUTPUT_DIR) / "screening";
    fs::create_directories(dir);
    return dir / name;
}

// A GeoJSON building whose footprint covers the wall's cell centres (columns a..b, with
// half a cell of margin) over every row.
fs::path writeBuilding(const std::string& name, const std::string& heightProperty) {
    const ElevationGrid ground = flatGround();
    const GridGeometry& g = ground.geometry;
    const double west = g.centreX(kWallFirst) - 0.4 * kCell,
                 east = g.centreX(kWallLast) + 0.4 * kCell;
    const double north = g.originY + kCell, south = g.originY - (kHeight + 1) * kCell;
    const fs::path path = scratch(name);
    std::ofstream out(path);
    out.precision(12);
    out << R"({"type":"FeatureCollection","crs":{"type":"name","properties":{"name":"urn:ogc:def:crs:EPSG::32725"}},)"
        << R"("features":[{"type":"Feature","properties":{)" << heightProperty << R"(},)"
        << R"("geometry":{"type":"Polygon","coordinates":[[[)" << west << "," << south << "],["
        << east << "," << south << "],[" << east << "," << north << "],[" << west << "," << north
        << "],[" << west << "," << south << "]]]}}]}";
    return path;
}

TEST(Screening, BuildingFootprintWithHeightAttribute) {
    const ElevationGrid ground = flatGround();
    ScreenLayer layer;
    layer.path = writeBuilding("wall.geojson", R"("height": 10.0)").string();
    auto screened = buildScreeningSurface(ground, std::span(&layer, 1));
    ASSERT_TRUE(screened.ok()) << screened.error().message;
    EXPECT_EQ(screened->buildingCells, std::size_t(kHeight * (kWallLast - kWallFirst + 1)));
    EXPECT_EQ(screened->surface.heights, wallSurface(ground).heights);
    expectWallShadow(ground, screened->surface, ViewshedMethod::Sweep, "building");
}

TEST(Screening, CanopyHeightRaster) {
    const ElevationGrid ground = flatGround();
    const GridGeometry& g = ground.geometry;
    const fs::path path = scratch("canopy.tif");
    GDALAllRegister();
    GDALDatasetH ds = GDALCreate(GDALGetDriverByName("GTiff"), path.c_str(), kWidth, kHeight, 1,
                                 GDT_Float32, nullptr);
    ASSERT_NE(ds, nullptr);
    double gt[6];
    g.geoTransform(gt);
    GDALSetGeoTransform(ds, gt);
    GDALSetProjection(ds, ground.crsWkt.c_str());
    std::vector<float> canopy(std::size_t(kWidth) * kHeight, 0.0f);
    for (int r = 0; r < kHeight; ++r)
        for (int c = kWallFirst; c <= kWallLast; ++c)
            canopy[std::size_t(r) * kWidth + std::size_t(c)] = float(kWallHeight);
    canopy[5] = -3.0f;  // negative: open ground
    ASSERT_EQ(GDALRasterIO(GDALGetRasterBand(ds, 1), GF_Write, 0, 0, kWidth, kHeight, canopy.data(),
                           kWidth, kHeight, GDT_Float32, 0, 0),
              CE_None);
    GDALClose(ds);
    ScreenLayer layer;
    layer.kind = ScreenLayer::Kind::Canopy;
    layer.path = path.string();
    auto screened = buildScreeningSurface(ground, std::span(&layer, 1));
    ASSERT_TRUE(screened.ok()) << screened.error().message;
    EXPECT_EQ(screened->canopyCells, std::size_t(kHeight * (kWallLast - kWallFirst + 1)));
    EXPECT_EQ(screened->surface.heights, wallSurface(ground).heights);
    expectWallShadow(ground, screened->surface, ViewshedMethod::Sweep, "canopy");
}

TEST(Screening, BadBuildingsFailWithPathAndReason) {
    const ElevationGrid ground = flatGround();
    const auto failure = [&](const fs::path& path, const std::string& attribute) {
        ScreenLayer layer;
        layer.path = path.string();
        layer.heightAttribute = attribute;
        auto screened = buildScreeningSurface(ground, std::span(&layer, 1));
        EXPECT_FALSE(screened.ok());
        return screened.ok() ? std::string() : screened.error().message;
    };
    const fs::path negative = writeBuilding("negative.geojson", R"("height": -4)");
    EXPECT_NE(failure(negative, "height").find("feature 0: the height 'height' must be a positive"),
              std::string::npos);
    const fs::path missing = writeBuilding("nullheight.geojson", R"("height": null, "name": "x")");
    EXPECT_NE(failure(missing, "height").find("'height'"), std::string::npos);
    const fs::path text = writeBuilding("text.geojson", R"("height": 3, "name": "tall")");
    EXPECT_NE(failure(text, "name").find("is not numeric"), std::string::npos);
    EXPECT_NE(failure(text, "storeys").find("no height attribute 'storeys'"), std::string::npos);
    EXPECT_NE(failure(scratch("absent.geojson"), "height").find("absent.geojson"),
              std::string::npos);
}

TEST(Screening, SurfaceOfAnotherGridIsAnError) {
    const ElevationGrid ground = flatGround();
    ElevationGrid other = ground;
    other.geometry.cellWidth = 2.0;
    const ViewshedTarget target{ground.geometry.centreX(5), ground.geometry.centreY(5), 10.0};
    EXPECT_FALSE(computeViewshed(ground, other, std::span(&target, 1), flatOptions()).ok());
}

}  // namespace
}  // namespace sylva
