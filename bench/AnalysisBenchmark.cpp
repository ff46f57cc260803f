#include "sylva/bench/AnalysisBenchmark.h"

#include <gdal.h>
#include <gdal_alg.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <optional>
#include <random>
#include <vector>

#include "sylva/core/analysis/Viewshed.h"

namespace sylva::bench {

namespace {

double bestSeconds(int repeats, const std::function<void()>& body) {
    double best = 1e300;
    for (int i = 0; i < repeats; ++i) {
        const auto start = std::chrono::steady_clock::now();
        body();
        best = std::min(
            best, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    }
    return best;
}

// The grid as an in-memory GDAL dataset (GDALViewshedGenerate's input).
GDALDatasetH memoryDataset(const ElevationGrid& grid) {
    const GridGeometry& g = grid.geometry;
    GDALDatasetH ds =
        GDALCreate(GDALGetDriverByName("MEM"), "", g.width, g.height, 1, GDT_Float32, nullptr);
    double gt[6];
    g.geoTransform(gt);
    GDALSetGeoTransform(ds, gt);
    GDALSetProjection(ds, grid.crsWkt.c_str());
    std::vector<float> z = grid.heights;
    if (GDALRasterIO(GDALGetRasterBand(ds, 1), GF_Write, 0, 0, g.width, g.height, z.data(), g.width,
                     g.height, GDT_Float32, 0, 0) != CE_None) {
        GDALClose(ds);
        return nullptr;
    }
    return ds;
}

std::size_t highestCell(const ElevationGrid& grid) {
    std::size_t best = 0;
    for (std::size_t i = 1; i < grid.heights.size(); ++i)
        if (grid.heights[i] > grid.heights[best])
            best = i;
    return best;
}

}  // namespace

std::string AnalysisBenchmarkResult::json() const {
    return metricsJson("analysis", metrics, {NumberFormat::Notation::General, 6});
}

Result<AnalysisBenchmarkResult> runAnalysisBenchmark(const AnalysisBenchmarkOptions& options) {
    const std::filesystem::path dem = options.dataFolder / "olinda" / "olinda_dem_utm25s.tif";
    if (!std::filesystem::exists(dem))
        return Error{dem.string() + " is missing; run scripts/fetch-samples"};
    auto info = readRasterInfo(dem.string());
    if (!info)
        return info.error();
    const GridGeometry& d = info->geometry;
    const double cell = options.resolution;
    const GridGeometry geometry{d.originX,
                                d.originY,
                                cell,
                                cell,
                                int(d.width * d.cellWidth / cell),
                                int(d.height * d.cellHeight / cell)};
    auto grid = readElevationGrid(dem.string(), geometry);
    if (!grid)
        return grid.error();
    const std::size_t top = highestCell(*grid);
    const ViewshedTarget target{geometry.centreX(double(top % std::size_t(geometry.width))),
                                geometry.centreY(double(top / std::size_t(geometry.width))), 120.0};
    ViewshedOptions vo;
    vo.earthRadius = 6378137.0;  // as GDAL 3.6, so agreement compares like with like
    vo.fraction = false;         // visibility only, what gdal_viewshed computes
    std::optional<ViewshedResult> ours;
    const double oursSeconds = bestSeconds(options.repeats, [&] {
        auto r = computeViewshed(*grid, std::span(&target, 1), vo);
        if (r)
            ours = std::move(*r);
    });
    if (!ours)
        return Error{"computeViewshed failed"};

    GDALAllRegister();
    GDALDatasetH input = memoryDataset(*grid);
    if (input == nullptr)
        return Error{"cannot make the GDAL MEM dataset"};
    std::vector<std::uint8_t> theirs(ours->cells());
    bool gdalOk = true;
    const double gdalSeconds = bestSeconds(options.repeats, [&] {
        GDALDatasetH out = GDALViewshedGenerate(
            GDALGetRasterBand(input, 1), "MEM", "", nullptr, target.x, target.y, target.height,
            vo.observerHeight, 255, 0, 0, 0, 1.0 - vo.refraction, GVM_Edge, 0, nullptr, nullptr,
            GVOT_NORMAL, nullptr);
        if (out == nullptr) {
            gdalOk = false;
            return;
        }
        gdalOk &=
            GDALRasterIO(GDALGetRasterBand(out, 1), GF_Read, 0, 0, geometry.width, geometry.height,
                         theirs.data(), geometry.width, geometry.height, GDT_Byte, 0, 0) == CE_None;
        GDALClose(out);
    });
    GDALClose(input);
    if (!gdalOk)
        return Error{std::string("GDALViewshedGenerate failed: ") + CPLGetLastErrorMsg()};
    std::size_t agree = 0;
    for (std::size_t i = 0; i < theirs.size(); ++i)
        agree += (theirs[i] == 255) == (ours->visible[i] == 1) ? 1 : 0;
    for (const auto& [mode, name] : {std::pair{GVM_Diagonal, "diagonal"},
                                     {GVM_Edge, "edge"},
                                     {GVM_Max, "max"},
                                     {GVM_Min, "min"}}) {
        GDALDatasetH modeInput = memoryDataset(*grid);
        GDALDatasetH out = GDALViewshedGenerate(
            GDALGetRasterBand(modeInput, 1), "MEM", "", nullptr, target.x, target.y, target.height,
            vo.observerHeight, 255, 0, 0, 0, 1.0 - vo.refraction, mode, 0, nullptr, nullptr,
            GVOT_NORMAL, nullptr);
        std::vector<std::uint8_t> other(ours->cells());
        if (out != nullptr && GDALRasterIO(GDALGetRasterBand(out, 1), GF_Read, 0, 0, geometry.width,
                                           geometry.height, other.data(), geometry.width,
                                           geometry.height, GDT_Byte, 0, 0) == CE_None) {
            std::size_t same = 0;
            for (std::size_t i = 0; i < other.size(); ++i)
                same += (other[i] == 255) == (ours->visible[i] == 1) ? 1 : 0;
            std::fprintf(stderr, "analysis: gdal mode %s agrees on %.4f of cells\n", name,
                         double(same) / double(other.size()));
        }
        if (out != nullptr)
            GDALClose(out);
        GDALClose(modeInput);
    }

    std::mt19937 random(19);
    std::vector<ViewshedTarget> targets;
    for (int i = 0; i < 20; ++i)
        targets.push_back({geometry.centreX(double(random() % unsigned(geometry.width))),
                           geometry.centreY(double(random() % unsigned(geometry.height))), 150.0});
    const double cumulativeSeconds =
        bestSeconds(1, [&] { (void)computeViewshed(*grid, targets, vo).ok(); });

    const double cells = double(ours->cells());
    AnalysisBenchmarkResult result;
    result.metrics = {{"ztv_cells_per_s", cells / oursSeconds},
                      {"gdal_viewshed_cells_per_s", cells / gdalSeconds},
                      {"ztv_speed_vs_gdal", gdalSeconds / oursSeconds},
                      {"ztv_agreement_gdal", double(agree) / cells},
                      {"cumulative_ztv_20_targets_s", cumulativeSeconds}};
    return result;
}

}  // namespace sylva::bench
