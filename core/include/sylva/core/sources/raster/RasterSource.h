// RasterSource (`source x : raster`): any raster GDAL can read (GeoTIFF/COG, VRT,
// JPEG2000 where the driver exists, PNG/JPEG with a world file ...) in any CRS,
// reprojected on the fly to the longitude/latitude tile grid (EPSG:4326).
//
// Algorithm, per tile: every texel centre (ImageTile::texelLongitude/Latitude) is
// transformed to the file's CRS with OGR/PROJ (per row, exactly at span end points and
// interpolated where that misses the exact midpoint by at most 0.125 source pixels,
// like GDAL's approximate transformer) and to pixel coordinates by the inverse
// geotransform; the window those pixels span (plus the kernel margin) is
// read with GDALRasterIO. When a texel covers f > 1 source pixels (minification) the
// window is read into a buffer f times smaller with average resampling, which makes
// GDAL use the file's overviews; the buffer is then resampled per texel with the
// chosen kernel (nearest, bilinear, or Keys cubic with a = -0.5 as in GDAL).
// Validity comes from GDAL's mask band (the file's nodata, alpha band or mask) and
// from `nodata`; kernels weight only valid pixels, and the kernel's valid weight is
// the texel's coverage in [0, 1] (0 outside the file or on no-data).
//
// Output, by kind:
//  - image: 4 channels, linear RGB + alpha = coverage (straight alpha; RGB is 0 where
//    coverage is 0). One band is replicated to grey, two give (b1, b2, 0). 8-bit bands
//    are divided by 255, then scale/offset, then decoded from sRGB unless srgb = false;
//    other types are taken as linear after scale/offset.
//  - elevation: 1 channel, metres (the band's own scale/offset, then scale/offset, then
//    the band's vertical unit: m, ft, US survey ft). Outside coverage the tile holds
//    `fill`. The coverage is a separate Mask source, coverage(), produced by the same
//    code, so the elevation tile stays one channel (what the terrain draws) while a
//    blend can still merge a local DEM into a global one.
//
// Bad input (missing, truncated or unreadable file, no or unknown CRS, missing band,
// unknown vertical unit) is detected when the source is built where possible; the
// source is still built, and every produce() then returns the same error, which names
// the file and the reason (the TileEvaluator reports it once per tile and remembers it).
// Thread safety: GDAL handles come from GdalDatasetPool (one per thread); produce()
// may run on several threads at once.
#pragma once

#include <array>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "sylva/core/sources/Source.h"
#include "sylva/core/sources/SourceBuildContext.h"

namespace sylva {

enum class RasterKind { Auto, Elevation, Image };
enum class Resampling { Nearest, Bilinear, Cubic };

struct RasterParameters {
    std::filesystem::path file;          // absolute, or relative to the working directory
    RasterKind kind = RasterKind::Auto;  // Auto: 1 band -> elevation, more -> image
    std::vector<int> bands;              // 1-based; empty: [1] or [1, 2, 3]
    std::optional<double> nodata;        // raw value marking no data (besides the file's)
    Resampling resampling = Resampling::Bilinear;
    double scale = 1.0;
    double offset = 0.0;
    // Radians, west, south, east, north: places a file without georeferencing on
    // WGS84 longitude/latitude (e.g. a world image); overrides the file's own.
    std::optional<std::array<double, 4>> bounds;
    std::optional<bool> srgb;  // image only; default: true for 8-bit bands
    double fill = 0.0;         // elevation outside coverage, metres
};

class RasterSource final : public Source {
public:
    // Opens and checks the file now (errors are kept for produce(), see above).
    static std::unique_ptr<RasterSource> open(std::string name, RasterParameters parameters);

    // From a `source x : raster` block; `file` is relative to the project folder.
    static Result<std::unique_ptr<Source>> create(const SourceBuildContext& context);

    ~RasterSource() override;

    Result<TilePointer> produce(const TileKey& key, TileProvider& provider) const override;
    std::vector<std::filesystem::path> files() const override { return {parameters_.file}; }

    // Elevation rasters: the Mask source of their coverage (owned by this source);
    // nullptr for images (their alpha is the coverage) and for coverage sources.
    const Source* coverage() const { return coverage_.get(); }
    // The error every produce() returns, if the file could not be used.
    const std::optional<Error>& openError() const { return openError_; }
    // Longitude/latitude bounds of the data in radians (west, south, east, north);
    // west > east never happens: files across the antimeridian give [-pi, pi].
    const std::array<double, 4>& lonLatBounds() const { return lonLatBounds_; }

    struct Info;  // what the file told us (GDAL-free, defined in RasterSource.cpp)

private:
    RasterSource(std::string name, PortType output, int channels, RasterParameters parameters,
                 std::shared_ptr<const Info> info, std::optional<Error> openError,
                 bool coverageOnly);

    RasterParameters parameters_;
    std::shared_ptr<const Info> info_;
    std::optional<Error> openError_;
    bool coverageOnly_;
    std::array<double, 4> lonLatBounds_{};
    std::unique_ptr<RasterSource> coverage_;
};

}  // namespace sylva
