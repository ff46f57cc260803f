#include "sylva/core/sources/raster/RasterSource.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <system_error>

#include <cpl_conv.h>
#include <cpl_error.h>
#include <cpl_string.h>
#include <gdal.h>
#include <ogr_srs_api.h>

#include "sylva/core/base/Hash.h"
#include "sylva/core/image/ColorSpace.h"
#include "sylva/core/sources/GdalDatasetPool.h"

namespace sylva {

struct RasterSource::Info {
    std::string path;
    int width = 0;
    int height = 0;
    std::array<double, 6> geoTransform{};
    std::array<double, 6> inverseTransform{};
    std::string wkt;
    bool geographic = false;
    bool wrapX = false;  // a geographic file spanning 360 degrees: columns wrap
    std::vector<int> bands;
    std::vector<double> bandScale;
    std::vector<double> bandOffset;
    bool byteData = false;
    double unitFactor = 1.0;  // metres per vertical unit
    // Every file GDAL reads for the dataset besides `path` (.aux.xml, .ovr, world files,
    // a VRT's sources), so their edits change the content hash too.
    std::vector<std::string> companionFiles;
};

namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

// Keys cubic convolution kernel, a = -0.5 (Keys 1981; GDAL's "cubic").
double keys(double t) {
    t = std::abs(t);
    if (t < 1.0) {
        return (1.5 * t - 2.5) * t * t + 1.0;
    }
    if (t < 2.0) {
        return ((-0.5 * t + 2.5) * t - 4.0) * t + 2.0;
    }
    return 0.0;
}

std::optional<double> metresPerUnit(std::string unit) {
    std::transform(unit.begin(), unit.end(), unit.begin(),
                   [](unsigned char c) { return std::tolower(c); });
    if (unit.empty() || unit == "m" || unit == "metre" || unit == "meter" || unit == "metres" ||
        unit == "meters") {
        return 1.0;
    }
    if (unit == "ft" || unit == "foot" || unit == "feet" || unit == "international foot") {
        return 0.3048;
    }
    if (unit == "us survey foot" || unit == "ftus" || unit == "us-ft") {
        return 1200.0 / 3937.0;
    }
    if (unit == "km" || unit == "kilometre" || unit == "kilometer") {
        return 1000.0;
    }
    return std::nullopt;
}

std::string lastGdalError(const char* fallback) {
    const char* message = CPLGetLastErrorMsg();
    return (message != nullptr && *message != '\0') ? std::string(message) : std::string(fallback);
}

// The geotransform (and its inverse) and the CRS as WKT: the file's own, or `bounds` on
// WGS84 longitude/latitude; whether the CRS is geographic and the columns wrap.
Status georeference(const RasterParameters& p, GDALDatasetH dataset, RasterSource::Info& info) {
    if (p.bounds) {
        const auto& b = *p.bounds;
        if (!(b[2] > b[0]) || !(b[3] > b[1])) {
            return Error{info.path +
                         ": bounds must be [west, south, east, north] with west < east "
                         "and south < north"};
        }
        info.geoTransform = {b[0] / kDegree,
                             (b[2] - b[0]) / kDegree / info.width,
                             0.0,
                             b[3] / kDegree,
                             0.0,
                             -(b[3] - b[1]) / kDegree / info.height};
        OGRSpatialReferenceH wgs84 = OSRNewSpatialReference(nullptr);
        OSRImportFromEPSG(wgs84, 4326);
        char* wkt = nullptr;
        OSRExportToWkt(wgs84, &wkt);
        info.wkt = wkt;
        CPLFree(wkt);
        OSRDestroySpatialReference(wgs84);
    } else {
        if (GDALGetGeoTransform(dataset, info.geoTransform.data()) != CE_None) {
            return Error{
                info.path +
                ": the file is not georeferenced (give bounds = [west, south, east, north])"};
        }
        OGRSpatialReferenceH srs = GDALGetSpatialRef(dataset);
        char* wkt = nullptr;
        if (srs == nullptr || OSRExportToWkt(srs, &wkt) != OGRERR_NONE || wkt == nullptr ||
            *wkt == '\0') {
            CPLFree(wkt);
            return Error{info.path +
                         ": the file has no coordinate reference system "
                         "(give bounds = [west, south, east, north] for lon/lat)"};
        }
        info.wkt = wkt;
        CPLFree(wkt);
    }
    if (GDALInvGeoTransform(info.geoTransform.data(), info.inverseTransform.data()) == 0) {
        return Error{info.path + ": the geotransform is not invertible"};
    }
    Result<void*> transform = GdalDatasetPool::fromLonLat(info.wkt);
    if (!transform) {
        return Error{info.path + ": " + transform.error().message};
    }
    {
        OGRSpatialReferenceH srs = OSRNewSpatialReference(info.wkt.c_str());
        info.geographic = srs != nullptr && OSRIsGeographic(srs) != 0;
        OSRDestroySpatialReference(srs);
    }
    info.wrapX = info.geographic && std::abs(info.geoTransform[1] * info.width) >= 359.999 &&
                 info.geoTransform[2] == 0.0;
    return Status::success();
}

// The bands (given, or [1] for elevation and single-band files, else [1, 2, 3]), the
// kind they make (Auto resolved), their scale/offset and data type, the vertical unit.
Status chooseBands(const RasterParameters& p, GDALDatasetH dataset, int bandCount, RasterKind& kind,
                   RasterSource::Info& info) {
    info.bands = p.bands;
    if (info.bands.empty()) {
        if (kind == RasterKind::Elevation || (kind == RasterKind::Auto && bandCount == 1)) {
            info.bands = {1};
        } else {
            info.bands = bandCount >= 3 ? std::vector<int>{1, 2, 3} : std::vector<int>{1};
        }
    }
    for (int band : info.bands) {
        if (band < 1 || band > bandCount) {
            return Error{info.path + ": band " + std::to_string(band) +
                         " does not exist (the file has " + std::to_string(bandCount) +
                         (bandCount == 1 ? " band)" : " bands)")};
        }
    }
    if (kind == RasterKind::Auto) {
        kind = info.bands.size() == 1 ? RasterKind::Elevation : RasterKind::Image;
    }
    if (kind == RasterKind::Elevation && info.bands.size() != 1) {
        return Error{info.path + ": an elevation raster takes exactly one band"};
    }
    if (kind == RasterKind::Image && info.bands.size() > 3) {
        return Error{info.path + ": an image raster takes one to three bands"};
    }
    info.byteData = true;
    for (int band : info.bands) {
        GDALRasterBandH h = GDALGetRasterBand(dataset, band);
        int hasScale = 0, hasOffset = 0;
        const double scale = GDALGetRasterScale(h, &hasScale);
        const double offset = GDALGetRasterOffset(h, &hasOffset);
        info.bandScale.push_back(hasScale ? scale : 1.0);
        info.bandOffset.push_back(hasOffset ? offset : 0.0);
        info.byteData = info.byteData && GDALGetRasterDataType(h) == GDT_Byte;
    }
    if (kind == RasterKind::Elevation) {
        const char* unit = GDALGetRasterUnitType(GDALGetRasterBand(dataset, info.bands[0]));
        std::optional<double> factor = metresPerUnit(unit != nullptr ? unit : "");
        if (!factor) {
            return Error{info.path + ": unknown vertical unit '" + std::string(unit) +
                         "' (expected m, ft or US survey foot)"};
        }
        info.unitFactor = *factor;
    }
    return Status::success();
}

// Reads everything produce() needs from the file; errors name the file.
Result<RasterSource::Info> probe(const RasterParameters& p, RasterKind& kind) {
    RasterSource::Info info;
    info.path = p.file.string();
    std::error_code ec;
    if (!std::filesystem::exists(p.file, ec)) {
        return Error{info.path + ": file not found"};
    }
    Result<void*> opened = GdalDatasetPool::dataset(info.path);
    if (!opened) {
        return opened.error();
    }
    GDALDatasetH dataset = opened.value();
    info.width = GDALGetRasterXSize(dataset);
    info.height = GDALGetRasterYSize(dataset);
    const int bandCount = GDALGetRasterCount(dataset);
    if (bandCount < 1 || info.width < 1 || info.height < 1) {
        return Error{info.path + ": the file has no raster bands"};
    }
    if (Status located = georeference(p, dataset, info); !located) {
        return located.error();
    }
    if (Status bands = chooseBands(p, dataset, bandCount, kind, info); !bands) {
        return bands.error();
    }
    if (char** list = GDALGetFileList(dataset); list != nullptr) {
        for (char** file = list; *file != nullptr; ++file) {
            if (std::string(*file) != info.path) {
                info.companionFiles.emplace_back(*file);
            }
        }
        CSLDestroy(list);
    }
    return info;
}

// Longitude/latitude bounds (radians) of the file's extent, densified along the edges.
std::array<double, 4> computeLonLatBounds(const RasterSource::Info& info) {
    const std::array<double, 4> world{-std::numbers::pi, -std::numbers::pi / 2, std::numbers::pi,
                                      std::numbers::pi / 2};
    OGRSpatialReferenceH source = OSRNewSpatialReference(info.wkt.c_str());
    OGRSpatialReferenceH wgs84 = OSRNewSpatialReference(nullptr);
    OSRImportFromEPSG(wgs84, 4326);
    OSRSetAxisMappingStrategy(wgs84, OAMS_TRADITIONAL_GIS_ORDER);
    OSRSetAxisMappingStrategy(source, OAMS_TRADITIONAL_GIS_ORDER);
    OGRCoordinateTransformationH toLonLat = OCTNewCoordinateTransformation(source, wgs84);
    std::array<double, 4> result = world;
    if (toLonLat != nullptr) {
        const double* g = info.geoTransform.data();
        std::vector<double> xs, ys;
        constexpr int kSteps = 32;
        for (int i = 0; i <= kSteps; ++i) {
            for (int j = 0; j <= kSteps; ++j) {
                if (i != 0 && i != kSteps && j != 0 && j != kSteps) {
                    continue;
                }
                const double px = info.width * double(i) / kSteps,
                             py = info.height * double(j) / kSteps;
                xs.push_back(g[0] + px * g[1] + py * g[2]);
                ys.push_back(g[3] + px * g[4] + py * g[5]);
            }
        }
        std::vector<int> ok(xs.size(), 0);
        OCTTransformEx(toLonLat, static_cast<int>(xs.size()), xs.data(), ys.data(), nullptr,
                       ok.data());
        double west = 1e9, east = -1e9, south = 1e9, north = -1e9;
        bool any = false, all = true;
        for (std::size_t i = 0; i < xs.size(); ++i) {
            if (!ok[i] || !std::isfinite(xs[i]) || !std::isfinite(ys[i])) {
                all = false;
                continue;
            }
            any = true;
            west = std::min(west, xs[i]);
            east = std::max(east, xs[i]);
            south = std::min(south, ys[i]);
            north = std::max(north, ys[i]);
        }
        OCTDestroyCoordinateTransformation(toLonLat);
        // Projected files whose edges do not all transform, or which cross the
        // antimeridian (a span above 180 degrees), are treated as unbounded in longitude.
        if (any && all) {
            const double marginLon = 0.01 * (east - west) + 1e-6;
            const double marginLat = 0.01 * (north - south) + 1e-6;
            result = {(west - marginLon) * kDegree, std::max(-90.0, south - marginLat) * kDegree,
                      (east + marginLon) * kDegree, std::min(90.0, north + marginLat) * kDegree};
            if (east - west > 180.0 && !info.geographic) {
                result[0] = world[0];
                result[2] = world[2];
            }
        }
    }
    OSRDestroySpatialReference(source);
    OSRDestroySpatialReference(wgs84);
    return result;
}

}  // namespace

RasterSource::RasterSource(std::string name, PortType output, int channels,
                           RasterParameters parameters, std::shared_ptr<const Info> info,
                           std::optional<Error> openError, bool coverageOnly)
    : Source(std::move(name), "raster", output, channels),
      parameters_(std::move(parameters)),
      info_(std::move(info)),
      openError_(std::move(openError)),
      coverageOnly_(coverageOnly) {
    const RasterParameters& p = parameters_;
    ContentHash hash;
    hash.add(p.file.string()).add(static_cast<int>(p.kind)).add(static_cast<int>(p.resampling));
    for (int band : p.bands) {
        hash.add(band);
    }
    hash.add(p.nodata.has_value()).add(p.nodata.value_or(0.0)).add(p.scale).add(p.offset);
    hash.add(p.bounds.has_value());
    for (double b : p.bounds.value_or(std::array<double, 4>{})) {
        hash.add(b);
    }
    hash.add(p.srgb.has_value() ? (*p.srgb ? 1 : 2) : 0).add(p.fill).add(coverageOnly);
    // The size and modification time (ns) of the file and of every file GDAL reads with
    // it: an edited file gives new tiles, in memory and in the disk tile cache.
    const auto addIdentity = [&hash](const std::filesystem::path& file) {
        std::error_code ec;
        const auto size = std::filesystem::file_size(file, ec);
        hash.add(static_cast<std::uint64_t>(ec ? 0 : size));
        const auto time = std::filesystem::last_write_time(file, ec);
        hash.add(static_cast<std::int64_t>(ec ? 0 : time.time_since_epoch().count()));
    };
    addIdentity(p.file);
    if (info_) {
        for (const std::string& file : info_->companionFiles) {
            hash.add(file);
            addIdentity(file);
        }
    }
    setParameterHash(hash.value());
    if (info_) {
        lonLatBounds_ = computeLonLatBounds(*info_);
    }
}

RasterSource::~RasterSource() = default;

std::unique_ptr<RasterSource> RasterSource::open(std::string name, RasterParameters parameters) {
    RasterKind kind = parameters.kind;
    Result<Info> info = probe(parameters, kind);
    std::optional<Error> error;
    std::shared_ptr<const Info> shared;
    if (info) {
        shared = std::make_shared<const Info>(std::move(info.value()));
    } else {
        error = info.error();
        if (kind == RasterKind::Auto) {
            kind = parameters.bands.size() == 1 ? RasterKind::Elevation : RasterKind::Image;
        }
    }
    const bool elevation = kind == RasterKind::Elevation;
    std::unique_ptr<RasterSource> source(
        new RasterSource(name, elevation ? PortType::Elevation : PortType::Image, elevation ? 1 : 4,
                         parameters, shared, error, false));
    if (elevation) {
        source->coverage_.reset(new RasterSource(name + ".coverage", PortType::Mask, 1, parameters,
                                                 shared, error, true));
    }
    return source;
}

namespace {

// Step 1: every texel centre of the tile (border included) in source pixel coordinates
// (full resolution), `ok` where the transformation succeeded, and the extent of those.
struct SourcePixels {
    std::vector<double> x, y;
    std::vector<int> ok;
    double minX = 1e300, maxX = -1e300, minY = 1e300, maxY = -1e300;
    bool empty() const { return minX > maxX; }
};

// One row of texel centres (longitudes `lon`, one latitude) to the file's CRS.
// Approximate transformer in the manner of GDALApproxTransform: the end points and the
// midpoint of a span are transformed exactly; if linear interpolation misses the
// midpoint by at most `tolerance` the span is interpolated, otherwise it is split in
// two. Exact at every transformed point.
void transformRow(OGRCoordinateTransformationH transform, const std::vector<double>& lon,
                  double latitude, double tolerance, double* rowX, double* rowY, int* rowOk) {
    const int stride = static_cast<int>(lon.size());
    auto exact = [&](int i) {
        rowX[i] = lon[i];
        rowY[i] = latitude;
        OCTTransformEx(transform, 1, &rowX[i], &rowY[i], nullptr, &rowOk[i]);
        rowOk[i] = rowOk[i] && std::isfinite(rowX[i]) && std::isfinite(rowY[i]);
    };
    auto span = [&](auto&& self, int i0, int i1) -> void {
        if (i1 - i0 <= 1) {
            return;
        }
        const int mid = (i0 + i1) / 2;
        exact(mid);
        if (rowOk[i0] && rowOk[i1] && rowOk[mid]) {
            const double t = double(mid - i0) / (i1 - i0);
            const double ex = rowX[i0] + (rowX[i1] - rowX[i0]) * t - rowX[mid];
            const double ey = rowY[i0] + (rowY[i1] - rowY[i0]) * t - rowY[mid];
            if (std::hypot(ex, ey) <= tolerance) {
                for (int i = i0 + 1; i < i1; ++i) {
                    if (i == mid) {
                        continue;
                    }
                    const double u = double(i - i0) / (i1 - i0);
                    rowX[i] = rowX[i0] + (rowX[i1] - rowX[i0]) * u;
                    rowY[i] = rowY[i0] + (rowY[i1] - rowY[i0]) * u;
                    rowOk[i] = 1;
                }
                return;
            }
        }
        self(self, i0, mid);
        self(self, mid, i1);
    };
    exact(0);
    exact(stride - 1);
    span(span, 0, stride - 1);
}

SourcePixels sourcePixels(const RasterSource::Info& info, const ImageTile& tile,
                          OGRCoordinateTransformationH transform) {
    const int stride = tile.stride();
    const int border = tile.border();
    const std::size_t count = static_cast<std::size_t>(stride) * stride;
    SourcePixels pixels;
    pixels.x.resize(count);
    pixels.y.resize(count);
    pixels.ok.assign(count, 0);
    const double* geo = info.geoTransform.data();
    // The tolerance: 0.125 source pixels.
    const double tolerance =
        0.125 * std::min(std::hypot(geo[1], geo[4]), std::hypot(geo[2], geo[5]));
    CPLPushErrorHandler(CPLQuietErrorHandler);
    std::vector<double> lon(stride);
    for (int j = 0; j < stride; ++j) {
        const double latitude = tile.texelLatitude(j - border) / kDegree;
        for (int i = 0; i < stride; ++i) {
            double longitude = tile.texelLongitude(i - border) / kDegree;
            if (info.geographic) {
                longitude = longitude - 360.0 * std::floor((longitude + 180.0) / 360.0);
            }
            lon[i] = longitude;
        }
        const std::size_t row = std::size_t(j) * stride;
        transformRow(transform, lon, latitude, tolerance, pixels.x.data() + row,
                     pixels.y.data() + row, pixels.ok.data() + row);
    }
    CPLPopErrorHandler();
    const double* inv = info.inverseTransform.data();
    for (std::size_t n = 0; n < count; ++n) {
        double& px = pixels.x[n];
        double& py = pixels.y[n];
        if (!pixels.ok[n] || !std::isfinite(px) || !std::isfinite(py)) {
            pixels.ok[n] = 0;
            continue;
        }
        const double x = px, y = py;
        px = inv[0] + x * inv[1] + y * inv[2];
        py = inv[3] + x * inv[4] + y * inv[5];
        if (info.wrapX) {
            px -= info.width * std::floor(px / info.width);
        }
        pixels.minX = std::min(pixels.minX, px);
        pixels.maxX = std::max(pixels.maxX, px);
        pixels.minY = std::min(pixels.minY, py);
        pixels.maxY = std::max(pixels.maxY, py);
    }
    return pixels;
}

// Step 2: source pixels per texel, from the centre texel's neighbours (or the extent).
double texelFootprint(const RasterSource::Info& info, const SourcePixels& pixels, int stride,
                      int border, int size) {
    const int c = border + size / 2;
    const std::size_t n0 = std::size_t(c) * stride + c, nx = n0 + 1, ny = n0 + stride;
    if (pixels.ok[n0] && pixels.ok[nx] && pixels.ok[ny]) {
        double dxx = pixels.x[nx] - pixels.x[n0];
        if (info.wrapX && std::abs(dxx) > info.width / 2.0) {
            dxx -= std::copysign(double(info.width), dxx);
        }
        return std::max(std::hypot(dxx, pixels.y[nx] - pixels.y[n0]),
                        std::hypot(pixels.x[ny] - pixels.x[n0], pixels.y[ny] - pixels.y[n0]));
    }
    return std::max(pixels.maxX - pixels.minX, pixels.maxY - pixels.minY) / size;
}

// Step 3: the source window [x0, x0 + width) × [y0, y0 + height) and the buffer it is
// read into, f times smaller when minifying (average resampling, so GDAL uses the
// file's overviews), per band and with GDAL's mask band.
struct SourceWindow {
    int x0 = 0, y0 = 0, width = 0, height = 0;
    int bufferWidth = 0, bufferHeight = 0;
    std::vector<std::vector<float>> values;  // per band
    std::vector<float> mask;
    bool empty() const { return width <= 0 || height <= 0; }
};

SourceWindow sourceWindow(const RasterSource::Info& info, const SourcePixels& pixels, double f,
                          int stride) {
    const double kernelMargin = 2.0 + f;
    SourceWindow window;
    int x0 = static_cast<int>(std::floor(pixels.minX - kernelMargin));
    int x1 = static_cast<int>(std::ceil(pixels.maxX + kernelMargin));
    int y0 = static_cast<int>(std::floor(pixels.minY - kernelMargin));
    int y1 = static_cast<int>(std::ceil(pixels.maxY + kernelMargin));
    if (info.wrapX) {
        x0 = 0;
        x1 = info.width;
    }
    x0 = std::clamp(x0, 0, info.width);
    x1 = std::clamp(x1, 0, info.width);
    y0 = std::clamp(y0, 0, info.height);
    y1 = std::clamp(y1, 0, info.height);
    window.x0 = x0;
    window.y0 = y0;
    window.width = x1 - x0;
    window.height = y1 - y0;
    if (window.empty()) {
        return window;
    }
    const int limit = 4 * stride;
    window.bufferWidth =
        std::clamp(static_cast<int>(std::ceil(window.width / f)), 1, std::max(limit, 1));
    window.bufferHeight =
        std::clamp(static_cast<int>(std::ceil(window.height / f)), 1, std::max(limit, 1));
    return window;
}

Status readWindow(const RasterSource::Info& info, GDALDatasetH dataset, Resampling resampling,
                  SourceWindow& window) {
    const bool minify = window.bufferWidth < window.width || window.bufferHeight < window.height;
    GDALRasterIOExtraArg extra;
    INIT_RASTERIO_EXTRA_ARG(extra);
    extra.eResampleAlg =
        (minify && resampling != Resampling::Nearest) ? GRIORA_Average : GRIORA_NearestNeighbour;
    const std::size_t bufferCount =
        static_cast<std::size_t>(window.bufferWidth) * window.bufferHeight;
    const int bandCount = static_cast<int>(info.bands.size());
    window.values.assign(bandCount, std::vector<float>(bufferCount));
    window.mask.assign(bufferCount, 0.0f);
    CPLPushErrorHandler(CPLQuietErrorHandler);
    CPLErrorReset();
    CPLErr err = CE_None;
    for (int b = 0; b < bandCount && err == CE_None; ++b) {
        GDALRasterBandH band = GDALGetRasterBand(dataset, info.bands[b]);
        err = GDALRasterIOEx(band, GF_Read, window.x0, window.y0, window.width, window.height,
                             window.values[b].data(), window.bufferWidth, window.bufferHeight,
                             GDT_Float32, 0, 0, &extra);
    }
    if (err == CE_None) {
        GDALRasterBandH maskBand = GDALGetMaskBand(GDALGetRasterBand(dataset, info.bands[0]));
        err = GDALRasterIOEx(maskBand, GF_Read, window.x0, window.y0, window.width, window.height,
                             window.mask.data(), window.bufferWidth, window.bufferHeight,
                             GDT_Float32, 0, 0, &extra);
    }
    const std::string reason = lastGdalError("read failed");
    CPLPopErrorHandler();
    if (err != CE_None) {
        return Error{info.path + ": cannot read pixels (" + reason + ")"};
    }
    return Status::success();
}

// Step 4: validity and units, per buffer pixel: the mask in [0, 1] (0 on `nodata` and
// non-finite values); values through the band's scale/offset, /255 for 8-bit images,
// the source's scale/offset, then sRGB decoding (images) or the vertical unit
// (elevation).
void decodeWindow(const RasterSource::Info& info, const RasterParameters& parameters, bool image,
                  SourceWindow& window) {
    const bool srgb = parameters.srgb.value_or(info.byteData);
    const int bandCount = static_cast<int>(info.bands.size());
    for (std::size_t n = 0; n < window.mask.size(); ++n) {
        float m = std::clamp(window.mask[n] / 255.0f, 0.0f, 1.0f);
        for (int b = 0; b < bandCount; ++b) {
            float& v = window.values[b][n];
            if (parameters.nodata && v == static_cast<float>(*parameters.nodata)) {
                m = 0.0f;
            }
            if (!std::isfinite(v)) {
                m = 0.0f;
                v = 0.0f;
                continue;
            }
            double x = v * info.bandScale[b] + info.bandOffset[b];
            if (image && info.byteData) {
                x /= 255.0;
            }
            x = x * parameters.scale + parameters.offset;
            if (image && srgb) {
                x = srgbToLinear(static_cast<float>(std::clamp(x, 0.0, 1.0)));
            } else if (!image) {
                x *= info.unitFactor;
            }
            v = static_cast<float>(x);
        }
        window.mask[n] = m;
    }
}

// Step 5: the kernel at one point of the buffer (u, v: buffer coordinates with pixel
// centres at integers). Bilinear weights of the valid pixels give the coverage (and the
// value unless cubic applies: Keys cubic where all 16 pixels are valid).
class WindowSampler {
public:
    WindowSampler(const RasterSource::Info& info, const SourceWindow& window)
        : window_(window), wrap_(info.wrapX), bands_(static_cast<int>(info.bands.size())) {}

    // Returns the coverage; `result` gets the band values where it is positive.
    double sample(Resampling resampling, double u, double v, float result[3]) const {
        for (int b = 0; b < 3; ++b) {
            result[b] = 0.0f;
        }
        if (resampling == Resampling::Nearest) {
            const int ni = column(static_cast<int>(std::floor(u + 0.5)));
            const int nj = static_cast<int>(std::floor(v + 0.5));
            const double coverage = maskAt(ni, nj);
            if (coverage > 0.0) {
                for (int b = 0; b < bands_; ++b) {
                    result[b] = window_.values[b][std::size_t(nj) * window_.bufferWidth + ni];
                }
            }
            return coverage;
        }
        const int iu = static_cast<int>(std::floor(u)), iv = static_cast<int>(std::floor(v));
        const double fu = u - iu, fv = v - iv;
        double weightSum = 0.0, sums[3] = {0, 0, 0};
        bool allValid = true;
        for (int dj = 0; dj < 2; ++dj) {
            for (int di = 0; di < 2; ++di) {
                const double w = (di ? fu : 1 - fu) * (dj ? fv : 1 - fv);
                const float m = maskAt(iu + di, iv + dj);
                allValid = allValid && m >= 1.0f;
                if (m <= 0.0f || w <= 0.0) {
                    continue;
                }
                const std::size_t at = std::size_t(iv + dj) * window_.bufferWidth + column(iu + di);
                weightSum += w * m;
                for (int b = 0; b < bands_; ++b) {
                    sums[b] += w * m * window_.values[b][at];
                }
            }
        }
        if (weightSum > 1e-9) {
            for (int b = 0; b < bands_; ++b) {
                result[b] = static_cast<float>(sums[b] / weightSum);
            }
        }
        if (resampling == Resampling::Cubic && allValid) {
            cubic(iu, iv, fu, fv, result);
        }
        return weightSum;
    }

private:
    // Keys cubic over the 4 × 4 pixels around (iu, iv), when all are valid.
    void cubic(int iu, int iv, double fu, double fv, float result[3]) const {
        double sums[3] = {0, 0, 0};
        for (int dj = -1; dj <= 2; ++dj) {
            const double wy = keys(fv - dj);
            for (int di = -1; di <= 2; ++di) {
                if (maskAt(iu + di, iv + dj) < 1.0f) {
                    return;
                }
                const double w = wy * keys(fu - di);
                const std::size_t at = std::size_t(iv + dj) * window_.bufferWidth + column(iu + di);
                for (int b = 0; b < bands_; ++b) {
                    sums[b] += w * window_.values[b][at];
                }
            }
        }
        for (int b = 0; b < bands_; ++b) {
            result[b] = static_cast<float>(sums[b]);
        }
    }
    int column(int i) const {
        if (wrap_) {
            return ((i % window_.bufferWidth) + window_.bufferWidth) % window_.bufferWidth;
        }
        return i;
    }
    float maskAt(int i, int j) const {
        i = column(i);
        if (i < 0 || j < 0 || i >= window_.bufferWidth || j >= window_.bufferHeight) {
            return 0.0f;
        }
        return window_.mask[std::size_t(j) * window_.bufferWidth + i];
    }

    const SourceWindow& window_;
    bool wrap_;
    int bands_;
};

}  // namespace

Result<TilePointer> RasterSource::produce(const TileKey& key, TileProvider& provider) const {
    if (openError_) {
        return *openError_;
    }
    const Info& info = *info_;
    const TileFormat& format = provider.format();
    auto tile = std::make_shared<ImageTile>(key, format.size, format.border, channels());
    const bool elevation = output() == PortType::Elevation;
    if (elevation) {
        std::fill(tile->texels().begin(), tile->texels().end(),
                  static_cast<float>(parameters_.fill));
    }
    // Tiles outside the data: no GDAL work at all.
    const double margin = 2.0 * tile->texelWidth();
    if (key.east() + margin < lonLatBounds_[0] || key.west() - margin > lonLatBounds_[2] ||
        key.north() + margin < lonLatBounds_[1] || key.south() - margin > lonLatBounds_[3]) {
        return TilePointer(std::move(tile));
    }
    Result<void*> opened = GdalDatasetPool::dataset(info.path);
    if (!opened) {
        return opened.error();
    }
    Result<void*> transformed = GdalDatasetPool::fromLonLat(info.wkt);
    if (!transformed) {
        return Error{info.path + ": " + transformed.error().message};
    }
    GDALDatasetH dataset = opened.value();
    auto transform = static_cast<OGRCoordinateTransformationH>(transformed.value());

    const int stride = tile->stride();
    const int border = format.border;
    const SourcePixels pixels = sourcePixels(info, *tile, transform);  // 1.
    if (pixels.empty()) {
        return TilePointer(std::move(tile));
    }
    const double f = std::max(texelFootprint(info, pixels, stride, border, format.size), 1.0);
    SourceWindow window = sourceWindow(info, pixels, f, stride);  // 3.
    if (window.empty()) {
        return TilePointer(std::move(tile));
    }
    if (Status read = readWindow(info, dataset, parameters_.resampling, window); !read) {
        return read.error();
    }
    const bool image =
        output() == PortType::Image || (coverageOnly_ && parameters_.kind == RasterKind::Image);
    decodeWindow(info, parameters_, image, window);  // 4.
    // 5. Resampling per texel.
    const WindowSampler sampler(info, window);
    const int bandCount = static_cast<int>(info.bands.size());
    const double sx = double(window.bufferWidth) / window.width;
    const double sy = double(window.bufferHeight) / window.height;
    float result[3];
    for (int j = 0; j < stride; ++j) {
        for (int i = 0; i < stride; ++i) {
            const std::size_t n = std::size_t(j) * stride + i;
            if (!pixels.ok[n]) {
                continue;
            }
            const double u = (pixels.x[n] - window.x0) * sx - 0.5;
            const double v = (pixels.y[n] - window.y0) * sy - 0.5;
            const double coverage = sampler.sample(parameters_.resampling, u, v, result);
            const int ix = i - border, iy = j - border;
            if (coverageOnly_) {
                tile->at(ix, iy, 0) = static_cast<float>(coverage);
            } else if (elevation) {
                if (coverage > 0.0) {
                    tile->at(ix, iy, 0) = result[0];
                }
            } else if (coverage > 0.0) {
                const float r = result[0];
                const float g = bandCount >= 2 ? result[1] : r;
                const float bl = bandCount >= 3 ? result[2] : (bandCount == 2 ? 0.0f : r);
                tile->at(ix, iy, 0) = std::max(r, 0.0f);
                tile->at(ix, iy, 1) = std::max(g, 0.0f);
                tile->at(ix, iy, 2) = std::max(bl, 0.0f);
                tile->at(ix, iy, 3) = static_cast<float>(std::clamp(coverage, 0.0, 1.0));
            }
        }
    }
    return TilePointer(std::move(tile));
}

Result<std::unique_ptr<Source>> RasterSource::create(const SourceBuildContext& context) {
    const BlockReader& reader = context.reader;
    RasterParameters p;
    const std::string file = reader.string("file");
    if (file.empty()) {
        return Error{reader.where("file") + "missing value for 'file'"};
    }
    std::filesystem::path path(file);
    p.file = path.is_absolute() ? path : (context.projectFolder / path).lexically_normal();
    auto word = [&](std::string_view name) -> std::string {
        const Value* v = reader.value(name);
        if (v == nullptr) {
            return {};
        }
        if (const Word* w = v->get<Word>()) {
            return w->text;
        }
        if (const std::string* s = v->get<std::string>()) {
            return *s;
        }
        return {};
    };
    const std::string kind = word("kind");
    p.kind = kind == "elevation" ? RasterKind::Elevation
             : kind == "image"   ? RasterKind::Image
                                 : RasterKind::Auto;
    const std::string resampling = word("resampling");
    p.resampling = resampling == "nearest" ? Resampling::Nearest
                   : resampling == "cubic" ? Resampling::Cubic
                                           : Resampling::Bilinear;
    if (const Value* bands = reader.value("bands")) {
        if (const ValueList* list = bands->get<ValueList>()) {
            for (const Value& item : *list) {
                const Quantity* q = item.get<Quantity>();
                if (q == nullptr || q->value < 1 || q->value != std::floor(q->value)) {
                    return Error{reader.where("bands") + "bands must be band numbers from 1"};
                }
                p.bands.push_back(static_cast<int>(q->value));
            }
        }
    }
    if (const Value* bounds = reader.value("bounds")) {
        const ValueList* list = bounds->get<ValueList>();
        if (list == nullptr || list->size() != 4) {
            return Error{reader.where("bounds") + "bounds must be [west, south, east, north]"};
        }
        std::array<double, 4> b{};
        for (int i = 0; i < 4; ++i) {
            const Quantity* q = (*list)[i].get<Quantity>();
            if (q == nullptr) {
                return Error{reader.where("bounds") + "bounds must be four angles"};
            }
            b[i] = q->value;
        }
        p.bounds = b;
    }
    p.nodata = reader.optionalNumber("nodata");
    p.scale = reader.optionalNumber("scale").value_or(1.0);
    p.offset = reader.optionalNumber("offset").value_or(0.0);
    p.fill = reader.optionalNumber("fill").value_or(0.0);
    if (reader.value("srgb") != nullptr) {
        p.srgb = reader.boolean("srgb", true);
    }
    return std::unique_ptr<Source>(open(context.block.name, std::move(p)));
}

}  // namespace sylva
