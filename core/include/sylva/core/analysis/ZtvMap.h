// ZtvMap: the styled PNG map of a zone of theoretical visibility (issue 19), drawn on the
// CPU into an RgbaImage (8-bit sRGB, core/image/Image.h) and written through ImageWriter
// (OIIO, atomic). The map covers exactly the analysis grid, north up, `scale` pixels per
// cell (so it has the grid's aspect), with, from bottom to top:
//   - a grey hillshade of the grid's elevation (Horn 1981, see hillshade());
//   - the ZTV colours: cells seen by k ≥ 1 targets get ztvCountColour(k, n) blended over
//     the relief with alpha kZtvAlpha (cells that see none stay grey); no-data cells are
//     hatched dark grey / light grey;
//   - distance rings around every target every ringSpacing(...) metres (the spacing
//     chosen for the first target);
//   - a north arrow in the free corner on the first target's side;
//   - a marker (black triangle, white rim) at every target;
//   - a legend in the corner opposite the first target (the swatch of each count as it
//     looks on flat ground, no data, the ring spacing, observer height, curvature and
//     refraction) and a scale bar in the other corner on the target's side (top/bottom),
//     drawn with BitmapFont; then the ring labels on the line from the first target to
//     the map's centre, where they hide neither.
// Blending works on the sRGB-encoded values, as image editors do. Units: grid and targets
// in the grid's CRS metres (ElevationGrid.h); heights in metres.
// Failures: writeZtvMap returns ImageWriter's error (path and reason); the drawing
// functions have no failure (mismatched grid and result sizes are programmer errors).
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "sylva/core/analysis/ElevationGrid.h"
#include "sylva/core/analysis/Viewshed.h"
#include "sylva/core/base/Result.h"
#include "sylva/core/image/Image.h"

namespace sylva {

// Alpha of the ZTV colours over the hillshade (semi-transparent so relief shows).
inline constexpr double kZtvAlpha = 0.5;
// Colour of the distance rings and of the target markers' core (sRGB).
inline constexpr std::array<std::uint8_t, 3> kZtvRingColour = {20, 70, 160};

// Lambertian shading 0..1 of every cell (row-major, the grid's geometry), NaN where the
// cell has no data. The gradient is Horn's (B. K. P. Horn, "Hill shading and the
// reflectance map", Proc. IEEE 69(1), 1981, 14–47): over the 3 × 3 neighbours a..i (a
// north-west, i south-east), dz/dx = ((c + 2f + i) − (a + 2d + g)) / (8·cellWidth) and
// dz/dy (northwards) = ((a + 2b + c) − (g + 2h + i)) / (8·cellHeight); the shade is
// max(0, n·s) with n the unit normal (−dz/dx, −dz/dy, 1)/|…| and s the unit vector to the
// sun at `azimuthDeg` (clockwise from north, default 315° = north-west) and
// `altitudeDeg` (default 45°) — the classic GDAL/ESRI hillshade. Neighbours outside the
// grid or without data take the centre's height. `zFactor` multiplies heights.
std::vector<float> hillshade(const ElevationGrid& grid, double azimuthDeg = 315.0,
                             double altitudeDeg = 45.0, double zFactor = 1.0);

// A north arrow: a dark triangle pointing up, its tip at (x, y), `size` px wide at the
// base and 2·size tall, an "N" under it (BitmapFont at fontScale, on white).
void drawNorthArrow(RgbaImage& image, int x, int y, int size, int fontScale);

// The opaque colour (sRGB) of cells seen by `count` of `targets` targets, 1 ≤ count ≤
// targets: a sequential yellow–orange–red ramp (ColorBrewer YlOrRd), one orange for a
// single target.
std::array<std::uint8_t, 3> ztvCountColour(int count, int targets);

// A round ring spacing in metres (1, 2 or 5 × 10^k) giving about 4 to 8 rings out to
// `maxDistance` metres (the farthest map corner from the target); > 0.
double ringSpacing(double maxDistance);

struct ZtvMapOptions {
    std::string title;         // e.g. the block's name
    ViewshedOptions viewshed;  // observer height, curvature and refraction for the legend
    int scale = 0;             // pixels per cell; 0 = ≥ 800 px on the longer side (≤ 16)
    // Hillshade height exaggeration; 0 = automatic: round(cell size / 30 m) clamped to
    // 1..5, since coarse cells flatten the slopes (x3 at 90 m); noted in the legend if not 1.
    double zFactor = 0.0;
};

// Where the legend drew what, for tests (pixel coordinates in the map).
struct ZtvMapLayout {
    int scale = 1;                                  // pixels per cell
    std::vector<std::array<int, 2>> swatchCentres;  // [k − 1]: the swatch of count k
    std::array<int, 4> legendBox = {0, 0, 0, 0};    // x0, y0, x1, y1 (exclusive)
    std::array<int, 4> scaleBarBox = {0, 0, 0, 0};  // x0, y0, x1, y1 (exclusive)
    double ringSpacing = 0.0;                       // metres
    double zFactor = 1.0;                           // the hillshade exaggeration used
};

struct ZtvMap {
    RgbaImage image;  // grid.width·scale × grid.height·scale, opaque
    ZtvMapLayout layout;
};

// Draws the whole map. `result` must be computed on `grid`'s geometry for `targets`.
ZtvMap drawZtvMap(const ElevationGrid& grid, const ViewshedResult& result,
                  std::span<const ViewshedTarget> targets, const ZtvMapOptions& options);

// Writes the map as an 8-bit sRGB PNG, atomically (ImageWriter::writeRgba8).
Status writeZtvMap(const std::filesystem::path& path, const ZtvMap& map);

}  // namespace sylva
