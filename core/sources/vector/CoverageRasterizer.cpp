#include "sylva/core/sources/vector/CoverageRasterizer.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "sylva/core/geo/Ellipsoid.h"

namespace sylva {
namespace {

// Overlap of a stroke cross-section [distance - half, distance + half] with a texel
// extent [-footprint / 2, footprint / 2], as a fraction of the footprint.
float crossCoverage(double distance, double half, double footprint) {
    const double overlap =
        std::min(distance + half, 0.5 * footprint) - std::max(distance - half, -0.5 * footprint);
    return static_cast<float>(std::clamp(overlap / footprint, 0.0, 1.0));
}

}  // namespace

CoverageRasterizer::CoverageRasterizer(const TileKey& key, int size, int border)
    : key_(key),
      size_(size),
      border_(border),
      width_(size + 2 * border),
      west_(key.west()),
      north_(key.north()),
      texelWidth_((key.east() - key.west()) / size),
      texelHeight_((key.north() - key.south()) / size) {}

glm::dvec2 CoverageRasterizer::toGrid(const glm::dvec2& lonLat, double longitudeShift) const {
    return {(lonLat.x + longitudeShift - west_) / texelWidth_ + border_,
            (north_ - lonLat.y) / texelHeight_ + border_};
}

glm::dvec2 CoverageRasterizer::toLonLat(const glm::dvec2& grid) const {
    return {west_ + (grid.x - border_) * texelWidth_, north_ - (grid.y - border_) * texelHeight_};
}

glm::dvec2 CoverageRasterizer::metresPerTexel(double y) const {
    const double latitude = std::clamp(north_ - (y - border_) * texelHeight_, -std::numbers::pi / 2,
                                       std::numbers::pi / 2);
    // Never exactly zero at the poles: a texel there still has a finite extent.
    const double east =
        std::max(Ellipsoid::primeVerticalRadius(latitude) * std::cos(latitude) * texelWidth_,
                 1e-9 * Ellipsoid::kSemiMajorAxis * texelWidth_);
    return {east, Ellipsoid::meridionalRadius(latitude) * texelHeight_};
}

void CoverageRasterizer::fillPolygon(const std::vector<std::vector<glm::dvec2>>& rings,
                                     double longitudeShift, std::vector<float>& coverage) const {
    const int w = width_;
    const std::size_t stride = std::size_t(w) + 2;
    std::vector<double> accumulation(stride * std::size_t(w), 0.0);
    // One piece of an edge inside row r, from x0 to x1, with signed height dy.
    auto addPiece = [&](int row, double x0, double x1, double dy) {
        double* acc = accumulation.data() + std::size_t(row) * stride;
        auto cell = [&](double xa, double xb, double h) {
            const double mid = 0.5 * (xa + xb);
            const int c = std::clamp(static_cast<int>(std::floor(mid)), 0, w - 1);
            const double inside = mid - c;
            acc[c] += h * (1.0 - inside);
            acc[c + 1] += h * inside;
        };
        if (x0 > x1) {
            std::swap(x0, x1);
        }
        const double length = x1 - x0;
        if (length < 1e-12) {
            if (x0 < 0.0) {
                acc[0] += dy;
            } else if (x0 < w) {
                cell(x0, x0, dy);
            }
            return;
        }
        if (x0 < 0.0) {  // the part left of the grid covers everything to its right
            acc[0] += dy * (std::min(x1, 0.0) - x0) / length;
        }
        const double lo = std::max(x0, 0.0), hi = std::min(x1, double(w));
        for (double start = lo; start < hi;) {
            const double end = std::min(hi, std::floor(start) + 1.0);
            cell(start, end, dy * (end - start) / length);
            start = end;
        }
    };
    for (const std::vector<glm::dvec2>& ring : rings) {
        for (std::size_t i = 0; i + 1 < ring.size(); ++i) {
            const glm::dvec2 a = toGrid(ring[i], longitudeShift);
            const glm::dvec2 b = toGrid(ring[i + 1], longitudeShift);
            if (a.y == b.y || (a.x >= w && b.x >= w)) {
                continue;
            }
            const double sign = b.y > a.y ? 1.0 : -1.0;
            const double yMin = std::max(std::min(a.y, b.y), 0.0);
            const double yMax = std::min(std::max(a.y, b.y), double(w));
            if (yMin >= yMax) {
                continue;
            }
            const double slope = (b.x - a.x) / (b.y - a.y);
            for (int row = static_cast<int>(std::floor(yMin)); row < w && row < yMax; ++row) {
                const double ya = std::max(yMin, double(row));
                const double yb = std::min(yMax, double(row + 1));
                if (yb <= ya) {
                    continue;
                }
                addPiece(row, a.x + (ya - a.y) * slope, a.x + (yb - a.y) * slope, sign * (yb - ya));
            }
        }
    }
    coverage.assign(std::size_t(w) * w, 0.0f);
    for (int row = 0; row < w; ++row) {
        double sum = 0.0;
        const double* acc = accumulation.data() + std::size_t(row) * stride;
        for (int c = 0; c < w; ++c) {
            sum += acc[c];
            coverage[std::size_t(row) * w + c] = static_cast<float>(std::min(std::abs(sum), 1.0));
        }
    }
}

void CoverageRasterizer::segment(const glm::dvec2& a, const glm::dvec2& b, double half,
                                 std::vector<float>& coverage) const {
    const int w = width_;
    // Reach in texels: the east metric is smallest at the tile's poleward edge, the
    // north metric at its equatorward edge; both are at the top or bottom row.
    const glm::dvec2 top = metresPerTexel(0.0), bottom = metresPerTexel(double(w));
    const double reachX = half / std::min(top.x, bottom.x) + 1.0;
    const double reachY = half / std::min(top.y, bottom.y) + 1.0;
    const int x0 = std::max(0, static_cast<int>(std::floor(std::min(a.x, b.x) - reachX)));
    const int x1 = std::min(w - 1, static_cast<int>(std::floor(std::max(a.x, b.x) + reachX)));
    const int y0 = std::max(0, static_cast<int>(std::floor(std::min(a.y, b.y) - reachY)));
    const int y1 = std::min(w - 1, static_cast<int>(std::floor(std::max(a.y, b.y) + reachY)));
    for (int gy = y0; gy <= y1; ++gy) {
        const glm::dvec2 k = metresPerTexel(gy + 0.5);
        const glm::dvec2 d = (b - a) * k;
        const double dd = glm::dot(d, d);
        for (int gx = x0; gx <= x1; ++gx) {
            const glm::dvec2 p = (glm::dvec2(gx + 0.5, gy + 0.5) - a) * k;
            const double t = dd > 0.0 ? std::clamp(glm::dot(p, d) / dd, 0.0, 1.0) : 0.0;
            const glm::dvec2 offset = p - t * d;
            const double distance = glm::length(offset);
            glm::dvec2 normal;
            if (distance > 1e-12) {
                normal = offset / distance;
            } else if (dd > 0.0) {
                normal = glm::dvec2(-d.y, d.x) / std::sqrt(dd);
            } else {
                normal = glm::dvec2(1.0, 0.0);
            }
            const double footprint = std::abs(normal.x) * k.x + std::abs(normal.y) * k.y;
            float& c = coverage[std::size_t(gy) * w + gx];
            c = std::max(c, crossCoverage(distance, half, footprint));
        }
    }
}

void CoverageRasterizer::strokeLines(const std::vector<std::vector<glm::dvec2>>& lines,
                                     double longitudeShift, double widthMetres,
                                     std::vector<float>& coverage) const {
    coverage.resize(std::size_t(width_) * width_, 0.0f);
    if (widthMetres <= 0.0) {
        return;
    }
    for (const std::vector<glm::dvec2>& line : lines) {
        if (line.size() == 1) {
            const glm::dvec2 p = toGrid(line.front(), longitudeShift);
            segment(p, p, 0.5 * widthMetres, coverage);
        }
        for (std::size_t i = 0; i + 1 < line.size(); ++i) {
            segment(toGrid(line[i], longitudeShift), toGrid(line[i + 1], longitudeShift),
                    0.5 * widthMetres, coverage);
        }
    }
}

void CoverageRasterizer::disc(const glm::dvec2& centreLonLat, double longitudeShift,
                              double radiusMetres, std::vector<float>& coverage) const {
    coverage.resize(std::size_t(width_) * width_, 0.0f);
    disc(centreLonLat, longitudeShift, radiusMetres, [&](std::size_t index, float a) {
        float& c = coverage[index];
        c = c + a - c * a;
    });
}

void CoverageRasterizer::disc(const glm::dvec2& centreLonLat, double longitudeShift,
                              double radiusMetres,
                              const std::function<void(std::size_t, float)>& visit) const {
    if (radiusMetres <= 0.0) {
        return;
    }
    const int w = width_;
    const glm::dvec2 centre = toGrid(centreLonLat, longitudeShift);
    const glm::dvec2 k = metresPerTexel(centre.y);
    if (2.0 * radiusMetres < std::min(k.x, k.y)) {
        const int gx = static_cast<int>(std::floor(centre.x)),
                  gy = static_cast<int>(std::floor(centre.y));
        if (gx >= 0 && gx < w && gy >= 0 && gy < w) {
            const double area = std::numbers::pi * radiusMetres * radiusMetres / (k.x * k.y);
            visit(std::size_t(gy) * w + gx, static_cast<float>(std::min(area, 1.0)));
        }
        return;
    }
    const double reachX = radiusMetres / k.x + 1.0, reachY = radiusMetres / k.y + 1.0;
    const int x0 = std::max(0, static_cast<int>(std::floor(centre.x - reachX)));
    const int x1 = std::min(w - 1, static_cast<int>(std::floor(centre.x + reachX)));
    const int y0 = std::max(0, static_cast<int>(std::floor(centre.y - reachY)));
    const int y1 = std::min(w - 1, static_cast<int>(std::floor(centre.y + reachY)));
    for (int gy = y0; gy <= y1; ++gy) {
        const glm::dvec2 m = metresPerTexel(gy + 0.5);
        for (int gx = x0; gx <= x1; ++gx) {
            const glm::dvec2 p = (glm::dvec2(gx + 0.5, gy + 0.5) - centre) * m;
            const double distance = glm::length(p);
            const glm::dvec2 normal = distance > 1e-12 ? p / distance : glm::dvec2(1.0, 0.0);
            const double footprint = std::abs(normal.x) * m.x + std::abs(normal.y) * m.y;
            // A disc is a stroke of zero length: the cross-section overlap from its rim.
            const double overlap = std::min(radiusMetres - distance + 0.5 * footprint, footprint);
            if (overlap > 0.0) {
                visit(std::size_t(gy) * w + gx, static_cast<float>(overlap / footprint));
            }
        }
    }
}

double CoverageRasterizer::quadrangleArea(double latitude1, double latitude2,
                                          double longitudeSpan) {
    const double e = std::sqrt(Ellipsoid::kEccentricitySquared);
    auto primitive = [&](double latitude) {
        const double s = std::sin(latitude);
        return s / (2.0 * (1.0 - e * e * s * s)) +
               std::log((1.0 + e * s) / (1.0 - e * s)) / (4.0 * e);
    };
    const double b = Ellipsoid::kSemiMinorAxis;
    return std::abs(b * b * longitudeSpan * (primitive(latitude2) - primitive(latitude1)));
}

double CoverageRasterizer::texelArea(int gy) const {
    const double top = std::clamp(north_ - (gy - border_) * texelHeight_, -std::numbers::pi / 2,
                                  std::numbers::pi / 2);
    const double bottom =
        std::clamp(top - texelHeight_, -std::numbers::pi / 2, std::numbers::pi / 2);
    return quadrangleArea(bottom, top, texelWidth_);
}

}  // namespace sylva
