#include "sylva/bench/TilesBenchmark.h"

#include <cpl_conv.h>
#include <gdal.h>
#include <gdal_alg.h>
#include <gdalwarper.h>
#include <ogr_srs_api.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <numbers>
#include <vector>

#include "sylva/bench/BenchmarkMetrics.h"
#include "sylva/core/geo/Ellipsoid.h"
#include "sylva/core/scheduler/Scheduler.h"
#include "sylva/core/scheduler/TileEvaluator.h"
#include "sylva/core/sources/GdalDatasetPool.h"
#include "sylva/core/sources/compose/BlendSource.h"
#include "sylva/core/sources/raster/AdjustSource.h"
#include "sylva/core/sources/raster/ConstantSource.h"
#include "sylva/core/sources/raster/NormalMapSource.h"
#include "sylva/core/sources/raster/RasterSource.h"
#include "sylva/core/terrain/Clipmap.h"
#include "sylva/core/terrain/LevelVisibility.h"

namespace sylva::bench {
namespace {

using Clock = std::chrono::steady_clock;
constexpr double kDegree = std::numbers::pi / 180.0;
const TileFormat kFormat{256, 2};

double secondsSince(Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
}

// A "Name:   N kB" line of /proc/self/status in MiB; 0 where /proc is absent.
double statusMegabytes(const char* name) {
    std::ifstream status("/proc/self/status");
    const std::string prefix = std::string(name) + ":";
    std::string line;
    while (std::getline(status, line)) {
        if (line.rfind(prefix, 0) == 0) {
            return std::stod(line.substr(prefix.size())) / 1024.0;  // kB
        }
    }
    return 0.0;
}

// The process's peak resident set (VmHWM), MiB.
double peakRssMegabytes() {
    return statusMegabytes("VmHWM");
}

// The process's current resident set (VmRSS), MiB.
double currentRssMegabytes() {
    return statusMegabytes("VmRSS");
}

// Resets VmHWM to the current RSS (Linux >= 4.0; ignored elsewhere).
void resetPeakRss() {
    std::ofstream clear("/proc/self/clear_refs");
    clear << "5";
}

// Every tile of (level, k = 0) touching the lon/lat bounds (radians: west, south,
// east, north).
std::vector<TileKey> tilesOver(const std::array<double, 4>& bounds, int level) {
    const int columns = TileKey::columns(level, 0), rows = TileKey::rows(level);
    const auto column = [&](double longitude) {
        return std::clamp(
            int(std::floor((longitude + std::numbers::pi) / (2 * std::numbers::pi) * columns)), 0,
            columns - 1);
    };
    const auto row = [&](double latitude) {
        return std::clamp(
            int(std::floor((std::numbers::pi / 2 - latitude) / std::numbers::pi * rows)), 0,
            rows - 1);
    };
    std::vector<TileKey> keys;
    for (int y = row(bounds[3]); y <= row(bounds[1]); ++y) {
        for (int x = column(bounds[0]); x <= column(bounds[2]); ++x) {
            keys.push_back(TileKey{level, 0, x, y});
        }
    }
    return keys;
}

struct Chain {
    std::unique_ptr<RasterSource> dem;
    std::unique_ptr<ConstantSource> base;
    std::unique_ptr<BlendSource> blended;
    std::unique_ptr<NormalMapSource> normals;
    std::unique_ptr<RasterSource> landsat;
    std::unique_ptr<AdjustSource> adjusted;
};

Result<Chain> makeChain(const std::filesystem::path& demFile,
                        const std::filesystem::path& imageFile) {
    Chain chain;
    RasterParameters dem;
    dem.file = demFile;
    dem.kind = RasterKind::Elevation;
    chain.dem = RasterSource::open("dem", dem);
    if (chain.dem->openError()) {
        return *chain.dem->openError();
    }
    chain.base = std::make_unique<ConstantSource>("base", 2.0);
    BlendParameters blend;
    blend.feather = 200.0;
    chain.blended =
        std::make_unique<BlendSource>("terrain", chain.base.get(), chain.dem.get(), nullptr, blend);
    chain.normals = std::make_unique<NormalMapSource>("terrain.normals", chain.blended.get(), 1.0);
    RasterParameters image;
    image.file = imageFile;
    image.kind = RasterKind::Image;
    image.bands = {3, 2, 1};
    chain.landsat = RasterSource::open("landsat", image);
    if (chain.landsat->openError()) {
        return *chain.landsat->openError();
    }
    AdjustParameters adjust;
    adjust.contrast = 1.2;
    adjust.saturation = 1.1;
    chain.adjusted =
        std::make_unique<AdjustSource>("landsat.adjusted", chain.landsat.get(), adjust);
    return chain;
}

void printSchedulerStatistics(const Scheduler& scheduler, std::size_t keys, double seconds) {
    std::fprintf(stderr, "RSS after the run: %.1f MiB (peak %.1f MiB); cache peak %.1f MiB\n",
                 currentRssMegabytes(), peakRssMegabytes(),
                 double(scheduler.peakCachedBytes()) / (1 << 20));
    std::fprintf(stderr, "%zu keys, %d workers, %.2f s:\n", keys, scheduler.workerCount(), seconds);
    for (const SchedulerStatistics& source : scheduler.statisticsPerSource()) {
        std::fprintf(
            stderr, "  %-18s produced %5zu  %8.3f s  hits %6zu  evictions %5zu  cached %6.1f MiB\n",
            source.name.c_str(), source.misses, source.produceSeconds, source.hits,
            source.evictions, double(source.bytes) / (1 << 20));
    }
}

// Produces both outputs of `keys` through a fresh Scheduler (cold caches); returns the
// seconds taken, or the first error.
Result<double> runChain(const Chain& chain, const std::vector<TileKey>& keys, int workers,
                        std::size_t budget, bool verbose) {
    SchedulerOptions options;
    options.format = kFormat;
    options.workers = workers;
    options.budgetBytes = budget;
    // Throughput is measured, not responsiveness: no render thread to yield to.
    options.workerNiceIncrement = 0;
    auto scheduler = std::make_unique<Scheduler>(options);
    std::vector<TileRequest> wanted;
    for (const TileKey& key : keys) {
        wanted.push_back({chain.normals.get(), key, key.level});
        wanted.push_back({chain.adjusted.get(), key, key.level});
    }
    if (verbose) {
        std::fprintf(stderr, "RSS before the run: %.1f MiB (peak so far %.1f MiB)\n",
                     currentRssMegabytes(), peakRssMegabytes());
    }
    const auto start = Clock::now();
    scheduler->setWanted(wanted);
    scheduler->waitIdle();
    const double seconds = secondsSince(start);
    if (verbose) {
        printSchedulerStatistics(*scheduler, keys.size(), seconds);
    }
    for (const TileRequest& request : wanted) {
        const TileLookup lookup = scheduler->tryGet(*request.source, request.key, 0);
        if (lookup.state == TileLookup::State::Failed) {
            return lookup.error;
        }
    }
    return seconds;
}

std::string wgs84Wkt() {
    OGRSpatialReferenceH srs = OSRNewSpatialReference(nullptr);
    OSRImportFromEPSG(srs, 4326);
    OSRSetAxisMappingStrategy(srs, OAMS_TRADITIONAL_GIS_ORDER);
    char* wkt = nullptr;
    OSRExportToWkt(srs, &wkt);
    std::string result = wkt;
    CPLFree(wkt);
    OSRDestroySpatialReference(srs);
    return result;
}

// GDAL's warper reprojecting `source` (band 1) into `target` through the approximate
// transformer; the centre texel read back, as a user of the tile would. False when the
// transformer cannot be built or the warp fails.
bool warpInto(GDALDatasetH source, GDALDatasetH target, int stride, bool hasNodata, double nodata,
              double& checksum) {
    void* exact = GDALCreateGenImgProjTransformer2(source, target, nullptr);
    if (exact == nullptr) {
        return false;
    }
    void* approximate = GDALCreateApproxTransformer(GDALGenImgProjTransform, exact, 0.125);
    GDALWarpOptions* options = GDALCreateWarpOptions();
    options->hSrcDS = source;
    options->hDstDS = target;
    options->nBandCount = 1;
    options->panSrcBands = static_cast<int*>(CPLMalloc(sizeof(int)));
    options->panDstBands = static_cast<int*>(CPLMalloc(sizeof(int)));
    options->panSrcBands[0] = options->panDstBands[0] = 1;
    options->eResampleAlg = GRA_Bilinear;
    options->eWorkingDataType = GDT_Float32;
    if (hasNodata) {
        options->padfSrcNoDataReal = static_cast<double*>(CPLMalloc(sizeof(double)));
        options->padfSrcNoDataReal[0] = nodata;
    }
    options->pfnTransformer = GDALApproxTransform;
    options->pTransformerArg = approximate;
    GDALWarpOperationH operation = GDALCreateWarpOperation(options);
    const CPLErr status = GDALChunkAndWarpImage(operation, 0, 0, stride, stride);
    float centre = 0.0f;
    if (GDALRasterIO(GDALGetRasterBand(target, 1), GF_Read, stride / 2, stride / 2, 1, 1, &centre,
                     1, 1, GDT_Float32, 0, 0) == CE_None) {
        checksum += centre;
    }
    GDALDestroyWarpOperation(operation);
    GDALDestroyApproxTransformer(approximate);
    GDALDestroyGenImgProjTransformer(exact);
    GDALDestroyWarpOptions(options);
    return status == CE_None;
}

// GDAL's warper reprojecting the DEM into each tile's 260² lon/lat grid (the tile's
// texel centres, border included). Returns seconds, or an error naming the file.
Result<double> gdalReprojection(const std::filesystem::path& demFile,
                                const std::vector<TileKey>& keys) {
    GDALDatasetH source = GDALOpen(demFile.c_str(), GA_ReadOnly);
    if (source == nullptr) {
        return Error{demFile.string() + ": GDAL cannot open it"};
    }
    const std::string wgs84 = wgs84Wkt();
    const int stride = kFormat.size + 2 * kFormat.border;
    int hasNodata = 0;
    const double nodata = GDALGetRasterNoDataValue(GDALGetRasterBand(source, 1), &hasNodata);
    const auto start = Clock::now();
    double checksum = 0.0;
    for (const TileKey& key : keys) {
        GDALDatasetH target =
            GDALCreate(GDALGetDriverByName("MEM"), "", stride, stride, 1, GDT_Float32, nullptr);
        const double width = (key.east() - key.west()) / kFormat.size / kDegree;
        const double height = (key.north() - key.south()) / kFormat.size / kDegree;
        double transform[6] = {key.west() / kDegree - kFormat.border * width,   width, 0,
                               key.north() / kDegree + kFormat.border * height, 0,     -height};
        GDALSetGeoTransform(target, transform);
        GDALSetProjection(target, wgs84.c_str());
        const bool warped = warpInto(source, target, stride, hasNodata != 0, nodata, checksum);
        GDALClose(target);
        if (!warped) {
            GDALClose(source);
            return Error{demFile.string() + ": GDAL warp failed for tile " + key.toString()};
        }
    }
    const double seconds = secondsSince(start);
    GDALClose(source);
    (void)checksum;
    return seconds;
}

// Bytes written into CPU clipmaps (height 1, normals 3, colour 4 float channels, the
// renderer's level offsets) along a slow flight, and the bytes that rebuilding every
// level each frame would write.
std::pair<double, double> clipmapUpdateBytes() {
    const int size = kFormat.size;
    constexpr int kMaxLevel = 24;
    struct Layer {
        int channels;
        int levelOffset;
    };
    const Layer layers[] = {{1, 2}, {3, 1}, {4, 1}};
    std::vector<Clipmap> clipmaps;
    std::vector<TilePointer> blank;  // one tile per layer: the bytes moved are what counts
    for (const Layer& layer : layers) {
        clipmaps.emplace_back(kMaxLevel + 1, size, layer.channels);
        blank.push_back(
            std::make_shared<ImageTile>(TileKey{}, size, kFormat.border, layer.channels));
    }
    // 20 s at 30 frames/s, 120 m above the ground at 15 m/s (a slow aircraft or a
    // drone), heading north-east over Olinda and turning slowly.
    const int frames = 600;
    double latitude = -8.0 * kDegree, longitude = -34.9 * kDegree;
    double heading = 45.0 * kDegree;
    const double step = 15.0 / 30.0, altitude = 120.0;
    double updated = 0.0, rebuilt = 0.0;
    for (int frame = 0; frame <= frames; ++frame) {
        const LevelRange levels = LevelVisibility::visibleLevels(altitude, altitude, 9000.0,
                                                                 60.0 * kDegree, 720, kMaxLevel);
        for (std::size_t layer = 0; layer < clipmaps.size(); ++layer) {
            const Clipmap::Fetch fetch = [&](const TileKey&) -> Result<TilePointer> {
                return blank[layer];
            };
            for (int level = std::max(0, levels.coarsest - 1); level <= levels.finest; ++level) {
                const ClipmapWindow window =
                    Clipmap::windowFor(level, latitude, longitude, size, layers[layer].levelOffset);
                if (!clipmaps[layer].valid(level) || !(clipmaps[layer].window(level) == window)) {
                    (void)clipmaps[layer].update(level, window, fetch);
                }
                if (frame > 0) {  // frame 0 builds everything once
                    rebuilt += double(size) * size * layers[layer].channels * sizeof(float);
                }
            }
            for (const Clipmap::Region& region : clipmaps[layer].takeDirtyRegions()) {
                if (frame > 0) {
                    updated += double(region.width) * region.height * layers[layer].channels *
                               sizeof(float);
                }
            }
        }
        const double radius = Ellipsoid::kMeanRadius;
        latitude += step * std::cos(heading) / radius;
        longitude += step * std::sin(heading) / (radius * std::cos(latitude));
        heading += 0.05 * kDegree;
    }
    return {updated, rebuilt};
}

// 1. Peak RSS of a long run under the cache budget (first, so VmHWM is its own).
Status measurePeakMemory(const Chain& chain, const TilesBenchmarkOptions& options,
                         std::map<std::string, double>& metrics) {
    const std::array<double, 4> bounds = chain.dem->lonLatBounds();
    std::vector<TileKey> keys;
    for (int level = 14; level <= 15; ++level) {
        const std::vector<TileKey> more = tilesOver(bounds, level);
        keys.insert(keys.end(), more.begin(), more.end());
    }
    // The binary maps Mesa (LLVM), GDAL, PROJ and OpenImageIO before any tile is
    // made (~180 MiB resident): the run's own memory is its peak above that.
    resetPeakRss();
    const double baseline = currentRssMegabytes();
    Result<double> seconds =
        runChain(chain, keys, 0, options.budgetMegabytes << 20, options.verbose);
    if (!seconds) {
        return seconds.error();
    }
    metrics["peak_rss_mb"] = peakRssMegabytes() - baseline;
    metrics["budget_mb"] = double(options.budgetMegabytes);
    return {};
}

// 2. Throughput of the reference chain with 1 and 2 workers, cold caches.
Status measureThroughput(const Chain& chain, const std::vector<TileKey>& keys, bool verbose,
                         std::map<std::string, double>& metrics) {
    // Interleaved and best of three, because the machine may be shared.
    double rates[2] = {0, 0};
    for (int repeat = 0; repeat < 3; ++repeat) {
        for (int workers = 1; workers <= 2; ++workers) {
            Result<double> seconds = runChain(chain, keys, workers, std::size_t{4} << 30, verbose);
            if (!seconds) {
                return seconds.error();
            }
            rates[workers - 1] =
                std::max(rates[workers - 1], double(keys.size()) / seconds.value());
        }
    }
    metrics["tiles_per_s_1_worker"] = rates[0];
    metrics["tiles_per_s_2_workers"] = rates[1];
    metrics["worker_scaling"] = rates[1] / std::max(rates[0], 1e-9);
    return {};
}

// 3. Reprojection alone, one thread each: the raster source against GDAL's warper.
Status measureReprojection(const Chain& chain, const std::filesystem::path& demFile,
                           const std::vector<TileKey>& keys,
                           std::map<std::string, double>& metrics) {
    double sylvaSeconds = 1e30, gdalSeconds = 1e30;
    for (int repeat = 0; repeat < 3; ++repeat) {
        TileEvaluator evaluator(kFormat);
        const auto start = Clock::now();
        for (const TileKey& key : keys) {
            Result<TilePointer> tile = evaluator.tile(*chain.dem, key);
            if (!tile) {
                return tile.error();
            }
        }
        sylvaSeconds = std::min(sylvaSeconds, secondsSince(start));
        Result<double> gdal = gdalReprojection(demFile, keys);
        if (!gdal) {
            return gdal.error();
        }
        gdalSeconds = std::min(gdalSeconds, gdal.value());
    }
    metrics["sylva_reprojection_tiles_per_s"] = double(keys.size()) / sylvaSeconds;
    metrics["gdal_tiles_per_s"] = double(keys.size()) / gdalSeconds;
    return {};
}

}  // namespace

std::string TilesBenchmarkResult::json() const {
    return metricsJson("tiles", metrics, {NumberFormat::Notation::General, 6});
}

Result<TilesBenchmarkResult> runTilesBenchmark(const TilesBenchmarkOptions& options) {
    const std::filesystem::path demFile = options.dataFolder / "olinda" / "olinda_dem_utm25s.tif";
    const std::filesystem::path imageFile = options.dataFolder / "olinda" / "L7_ETMs.tif";
    for (const std::filesystem::path& file : {demFile, imageFile}) {
        if (!std::filesystem::exists(file)) {
            return Error{"sample file '" + file.string() +
                         "' is missing; run scripts/fetch-samples (or give --data DIR)"};
        }
    }
    GdalDatasetPool::registerDrivers();
    Result<Chain> chain = makeChain(demFile, imageFile);
    if (!chain) {
        return chain.error();
    }
    TilesBenchmarkResult result;
    if (Status measured = measurePeakMemory(*chain, options, result.metrics); !measured) {
        return measured.error();
    }
    const std::vector<TileKey> keys = tilesOver(chain->dem->lonLatBounds(), 14);
    if (Status measured = measureThroughput(*chain, keys, options.verbose, result.metrics);
        !measured) {
        return measured.error();
    }
    if (Status measured = measureReprojection(*chain, demFile, keys, result.metrics); !measured) {
        return measured.error();
    }
    // 4. Clipmap update bytes along a slow flight against full rebuilds.
    const auto [updated, rebuilt] = clipmapUpdateBytes();
    result.metrics["update_bytes_ratio"] = updated / std::max(rebuilt, 1.0);
    return result;
}

}  // namespace sylva::bench
