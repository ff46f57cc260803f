// CoverageRasterizer: anti-aliased coverage of vector geometry on the texel grid of
// one tile (interior and border), shared by rasterize, elevation_edit and plants.
//
// Grid: texel (ix, iy) of the tile (ix, iy in [-border, size + border)) is grid cell
// (gx, gy) = (ix + border, iy + border), spanning grid x in [gx, gx + 1) where
//   x = (longitude - west) / texelWidth + border,  y = (north - latitude) / texelHeight + border.
// Coverage buffers are width() x width() floats, row-major from the north.
//
// Polygons: exact area coverage (the fraction of the texel's longitude/latitude
// rectangle inside the polygon, non-zero winding) by signed-area accumulation: each
// edge adds, per texel it crosses, its signed height times the part of the texel to
// its right, and the rest of its height to the next texel; a prefix sum along the row
// then gives the covered fraction (the accumulation-buffer scheme of outline font
// rasterizers, e.g. Raph Levien's font-rs). No supersampling, no jaggies.
//
// Lines and discs: widths in metres on the WGS84 ellipsoid, measured in the local
// east/north metric of each texel (N cos(lat) per radian of longitude, M per radian
// of latitude), so they are right at any latitude. A texel's coverage is the overlap
// of the stroke's cross-section [d - w/2, d + w/2] (d = distance of the texel centre
// from the segment, round caps) with the texel's extent across the stroke: a box
// filter, so the summed coverage across a line is its width.
#pragma once

#include <functional>
#include <vector>

#include <glm/glm.hpp>

#include "sylva/core/tiles/TileKey.h"

namespace sylva {

class CoverageRasterizer {
public:
    CoverageRasterizer(const TileKey& key, int size, int border);

    int width() const { return width_; }
    // Grid coordinates of a longitude/latitude (radians) plus a longitude shift.
    glm::dvec2 toGrid(const glm::dvec2& lonLat, double longitudeShift = 0.0) const;
    // Longitude/latitude of grid coordinates.
    glm::dvec2 toLonLat(const glm::dvec2& grid) const;
    // Metres per grid unit eastwards and northwards at grid row y (texel centre).
    glm::dvec2 metresPerTexel(double y) const;

    // Coverage in [0, 1] of the polygon given by closed rings, written to
    // `coverage` (resized to width()², overwritten).
    void fillPolygon(const std::vector<std::vector<glm::dvec2>>& rings, double longitudeShift,
                     std::vector<float>& coverage) const;

    // Strokes polylines `widthMetres` wide (round joins and caps), combining with
    // what `coverage` holds by max (so joins are not counted twice).
    void strokeLines(const std::vector<std::vector<glm::dvec2>>& lines, double longitudeShift,
                     double widthMetres, std::vector<float>& coverage) const;

    // A disc of `radiusMetres` about `centre`, composited over `coverage`
    // (c = c + a - c a). Discs smaller than a texel add their area fraction to the
    // texel holding their centre, so dense small discs still average correctly.
    void disc(const glm::dvec2& centre, double longitudeShift, double radiusMetres,
              std::vector<float>& coverage) const;
    // The same disc, as (texel index, coverage) pairs handed to `visit`.
    void disc(const glm::dvec2& centre, double longitudeShift, double radiusMetres,
              const std::function<void(std::size_t index, float coverage)>& visit) const;

    // Area of the texel (gx, gy) on the WGS84 ellipsoid, square metres (exact for the
    // longitude/latitude rectangle: integral of M N cos(lat)).
    double texelArea(int gy) const;
    // Area of the longitude/latitude rectangle [lat1, lat2] x dLongitude on WGS84.
    static double quadrangleArea(double latitude1, double latitude2, double longitudeSpan);

private:
    void segment(const glm::dvec2& a, const glm::dvec2& b, double halfWidth,
                 std::vector<float>& coverage) const;

    TileKey key_;
    int size_;
    int border_;
    int width_;
    double west_, north_, texelWidth_, texelHeight_;
};

}  // namespace sylva
