#include "sylva/core/analysis/ZtvMap.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "sylva/core/base/Check.h"
#include "sylva/core/image/BitmapFont.h"
#include "sylva/core/image/ImageWriter.h"

namespace sylva {

namespace {

using Rgb = std::array<std::uint8_t, 3>;

double roundDistance(double target);

constexpr Rgb kBlack = {0, 0, 0};
constexpr Rgb kWhite = {255, 255, 255};
constexpr Rgb kHatchDark = {70, 70, 70};
constexpr Rgb kHatchLight = {205, 205, 205};
constexpr Rgb kRingLabel = {10, 40, 110};  // darker than the rings, so ring pixels are lines

// Grey of a shade 0..1: an ambient floor so slopes away from the sun keep detail.
double greyOf(double shade) {
    return 255.0 * (0.2 + 0.8 * shade);
}

std::uint8_t blend(double under, std::uint8_t over, double alpha) {
    return std::uint8_t(std::lround(under * (1.0 - alpha) + double(over) * alpha));
}

void put(RgbaImage& image, int x, int y, const Rgb& rgb) {
    if (x < 0 || y < 0 || x >= image.width || y >= image.height)
        return;
    std::uint8_t* p = image.at(x, y);
    p[0] = rgb[0];
    p[1] = rgb[1];
    p[2] = rgb[2];
    p[3] = 255;
}

void fill(RgbaImage& image, int x0, int y0, int x1, int y1, const Rgb& rgb) {
    fillPixels(image, x0, y0, x1, y1, {rgb[0], rgb[1], rgb[2], std::uint8_t(255)});
}

void text(RgbaImage& image, int x, int y, const std::string& s, int scale, const Rgb& rgb) {
    BitmapFont::draw(image, x, y, s, scale, rgb.data());
}

Rgb hatch(int x, int y, int scale) {
    return ((x + y) / std::max(1, scale)) % 3 == 0 ? kHatchDark : kHatchLight;
}

// Colour of a map pixel over a cell: relief grey, the count's colour blended over it.
Rgb cellColour(double grey, int count, int targets) {
    const auto g = std::uint8_t(std::lround(std::clamp(grey, 0.0, 255.0)));
    if (count <= 0)
        return {g, g, g};
    const Rgb c = ztvCountColour(std::min(count, targets), targets);
    return {blend(g, c[0], kZtvAlpha), blend(g, c[1], kZtvAlpha), blend(g, c[2], kZtvAlpha)};
}

// Bilinear shade at fractional cell coordinates; the nearest cell's when a corner lacks data.
double shadeAt(const std::vector<float>& shade, const GridGeometry& g, double col, double row) {
    col = std::clamp(col, 0.0, double(g.width - 1));
    row = std::clamp(row, 0.0, double(g.height - 1));
    const int c0 = std::min(int(col), g.width - 2 < 0 ? 0 : g.width - 2);
    const int r0 = std::min(int(row), g.height - 2 < 0 ? 0 : g.height - 2);
    const int c1 = std::min(c0 + 1, g.width - 1), r1 = std::min(r0 + 1, g.height - 1);
    auto at = [&](int c, int r) { return double(shade[std::size_t(r) * g.width + c]); };
    const double fc = col - c0, fr = row - r0;
    const double v = (at(c0, r0) * (1 - fc) + at(c1, r0) * fc) * (1 - fr) +
                     (at(c0, r1) * (1 - fc) + at(c1, r1) * fc) * fr;
    return std::isnan(v) ? at(int(std::lround(col)), int(std::lround(row))) : v;
}

// The relief and the ZTV colours, `scale` pixels per cell.
void drawCells(RgbaImage& image, const std::vector<float>& shade, const ViewshedResult& result,
               int targets, int scale) {
    const GridGeometry& g = result.geometry;
    for (int y = 0; y < image.height; ++y) {
        for (int x = 0; x < image.width; ++x) {
            const std::size_t cell = std::size_t(y / scale) * g.width + std::size_t(x / scale);
            if (std::isnan(shade[cell]) || std::isnan(result.fraction[cell])) {
                put(image, x, y, hatch(x, y, std::max(1, scale / 2)));
                continue;
            }
            const double s = shadeAt(shade, g, (x + 0.5) / scale - 0.5, (y + 0.5) / scale - 0.5);
            put(image, x, y, cellColour(greyOf(s), result.count[cell], targets));
        }
    }
}

struct Corner {
    bool right = false;
    bool bottom = false;
};

struct Frame {
    GridGeometry g;
    int scale = 1;
    double px(double x) const { return (x - g.originX) / g.cellWidth * scale; }
    double py(double y) const { return (g.originY - y) / g.cellHeight * scale; }
    double metresPerPixel() const { return g.cellWidth / scale; }
};

std::string distanceLabel(double metres) {
    char buffer[32];
    if (metres >= 1000.0)
        std::snprintf(buffer, sizeof buffer, "%g km", metres / 1000.0);
    else
        std::snprintf(buffer, sizeof buffer, "%g m", metres);
    return buffer;
}

double farthestCorner(const GridGeometry& g, const ViewshedTarget& t) {
    const double dx =
        std::max(std::abs(t.x - g.originX), std::abs(g.originX + g.width * g.cellWidth - t.x));
    const double dy =
        std::max(std::abs(g.originY - t.y), std::abs(t.y - (g.originY - g.height * g.cellHeight)));
    return std::hypot(dx, dy);
}

// Metres from map pixel (x, y) to the nearest target.
double nearestTargetDistance(const Frame& f, std::span<const ViewshedTarget> targets, double x,
                             double y) {
    double nearest = INFINITY;
    for (const ViewshedTarget& t : targets)
        nearest = std::min(nearest, std::hypot(x - f.px(t.x), y - f.py(t.y)));
    return nearest * f.metresPerPixel();
}

// Ring lines at multiples of `spacing` metres from the nearest target (one target: circles;
// a wind farm: the envelope of its turbines' circles, as ZTV maps draw distance from the
// nearest turbine): pixels whose centre lies within 0.8 px of such a distance.
void drawRingLines(RgbaImage& image, const Frame& f, std::span<const ViewshedTarget> targets,
                   double spacing) {
    const double half = 0.8 * f.metresPerPixel();
    for (int y = 0; y < image.height; ++y) {
        for (int x = 0; x < image.width; ++x) {
            const double d = nearestTargetDistance(f, targets, x + 0.5, y + 0.5);
            const double m = std::round(d / spacing);
            if (m >= 1.0 && std::abs(d - m * spacing) <= half)
                put(image, x, y, kZtvRingColour);
        }
    }
}

bool overlaps(const std::array<int, 4>& a, const std::array<int, 4>& b) {
    return a[0] < b[2] && b[0] < a[2] && a[1] < b[3] && b[1] < a[3];
}

// Pixels along the ray (ux, uy) from (tx, ty) to where the nearest-target distance first
// reaches `metres` (the ray's length when it never does): half-pixel steps, then bisection.
double rayDistanceTo(const Frame& f, std::span<const ViewshedTarget> targets, double tx, double ty,
                     double ux, double uy, double metres, double length) {
    auto reached = [&](double r) {
        return nearestTargetDistance(f, targets, tx + r * ux, ty + r * uy) >= metres;
    };
    double low = 0.0, high = 0.5;
    while (high <= length && !reached(high)) {
        low = high;
        high += 0.5;
    }
    if (high > length)
        return length;
    for (int step = 0; step < 12; ++step) {
        const double mid = 0.5 * (low + high);
        (reached(mid) ? high : low) = mid;
    }
    return high;
}

// A label on each ring where it crosses the line from the first target towards the map's
// centre, skipped where it would leave the map or cover one of `avoid`.
void drawRingLabels(RgbaImage& image, const Frame& f, std::span<const ViewshedTarget> targets,
                    double spacing, int fontScale, const std::vector<std::array<int, 4>>& avoid) {
    const ViewshedTarget& t = targets.front();
    const double tx = f.px(t.x), ty = f.py(t.y);
    double ux = image.width / 2.0 - tx, uy = image.height / 2.0 - ty;
    const double length = std::hypot(ux, uy);
    ux = length > 1.0 ? ux / length : 0.0;
    uy = length > 1.0 ? uy / length : -1.0;
    const int th = BitmapFont::textHeight(fontScale);
    for (int m = 1; m * spacing <= farthestCorner(f.g, t); ++m) {
        const double r = rayDistanceTo(f, targets, tx, ty, ux, uy, m * spacing,
                                       2.0 * (image.width + image.height));
        const std::string label = distanceLabel(m * spacing);
        const int w = BitmapFont::textWidth(label, fontScale);
        const int lx = int(std::lround(tx + r * ux)) - w / 2;
        const int ly = int(std::lround(ty + r * uy)) - th / 2;
        const std::array<int, 4> box = {lx - fontScale, ly - fontScale, lx + w + fontScale,
                                        ly + th + fontScale};
        bool hidden = box[0] < 0 || box[1] < 0 || box[2] > image.width || box[3] > image.height;
        for (const auto& other : avoid)
            hidden = hidden || overlaps(box, other);
        if (!hidden)
            BitmapFont::draw(image, lx, ly, label, fontScale, kRingLabel.data(), kWhite.data());
    }
}

// A target: a white-rimmed black triangle pointing up at the target's position.
void drawTarget(RgbaImage& image, const Frame& f, const ViewshedTarget& t, int size) {
    const int cx = int(std::lround(f.px(t.x))), cy = int(std::lround(f.py(t.y)));
    for (int pass = 0; pass < 2; ++pass) {
        const int s = pass == 0 ? size + 2 : size;
        const Rgb& colour = pass == 0 ? kWhite : kBlack;
        for (int dy = -s; dy <= s; ++dy) {
            const int half = (dy + s) / 2;
            for (int dx = -half; dx <= half; ++dx)
                put(image, cx + dx, cy + dy, colour);
        }
    }
    put(image, cx, cy, kWhite);
}

// The top-left corner of a w × h box in a corner of the image, `margin` pixels in.
std::array<int, 2> inCorner(const RgbaImage& image, const Corner& c, int w, int h, int margin) {
    return {c.right ? image.width - margin - w : margin,
            c.bottom ? image.height - margin - h : margin};
}

// A scale bar of about a fifth of the map's width in `corner`; returns its box.
std::array<int, 4> drawScaleBar(RgbaImage& image, const Frame& f, int fontScale,
                                const Corner& corner) {
    const double metres = roundDistance(image.width * f.metresPerPixel() / 5.0);
    const int length = int(std::lround(metres / f.metresPerPixel()));
    const int margin = 6 * fontScale, barHeight = 3 * fontScale;
    const std::string label = distanceLabel(metres);
    const int th = BitmapFont::textHeight(fontScale);
    const auto at =
        inCorner(image, corner, length + 2 * margin, barHeight + th + 3 * margin, margin);
    const std::array<int, 4> box = {at[0], at[1], at[0] + length + 2 * margin,
                                    at[1] + barHeight + th + 3 * margin};
    const int x0 = box[0] + margin, x1 = x0 + length;
    const int y1 = box[3] - margin, y0 = y1 - barHeight;
    fill(image, box[0], box[1], box[2], box[3], kWhite);
    fill(image, x0 - 1, y0 - 1, x1 + 1, y1 + 1, kBlack);
    for (int i = 0; i < 4; ++i)
        if (i % 2 == 1)
            fill(image, x0 + i * length / 4, y0, x0 + (i + 1) * length / 4, y1, kWhite);
    text(image, x0, box[1] + margin / 2, "0", fontScale, kBlack);
    text(image, x1 - BitmapFont::textWidth(label, fontScale), box[1] + margin / 2, label, fontScale,
         kBlack);
    return box;
}

std::vector<std::string> legendNotes(const ZtvMapOptions& o, double spacing, int targets,
                                     double zFactor) {
    char buffer[96];
    std::vector<std::string> notes;
    std::snprintf(buffer, sizeof buffer, "rings every %s %s", distanceLabel(spacing).c_str(),
                  targets == 1 ? "from the target" : "to nearest target");
    notes.emplace_back(buffer);
    std::snprintf(buffer, sizeof buffer, "observer %g m above ground", o.viewshed.observerHeight);
    notes.emplace_back(buffer);
    if (o.viewshed.curvature)
        std::snprintf(buffer, sizeof buffer, "curvature on, refraction k = %g",
                      o.viewshed.refraction);
    else
        std::snprintf(buffer, sizeof buffer, "curvature and refraction off");
    notes.emplace_back(buffer);
    if (zFactor != 1.0) {
        std::snprintf(buffer, sizeof buffer, "relief shading x%g", zFactor);
        notes.emplace_back(buffer);
    }
    return notes;
}

// The legend, top left: title, one swatch per count (as it looks on flat ground), no data,
// the notes. Fills the layout's swatch centres and box.
void drawLegend(RgbaImage& image, const ZtvMapOptions& o, int targets, bool noData, int fontScale,
                const Corner& corner, ZtvMapLayout& layout) {
    const int th = BitmapFont::textHeight(fontScale), pad = 4 * fontScale;
    const int swatch = th;
    const std::vector<std::string> notes =
        legendNotes(o, layout.ringSpacing, targets, layout.zFactor);
    std::vector<std::string> rows;
    rows.push_back("ZTV " + o.title + ": targets visible");
    rows.emplace_back("not visible");
    for (int k = 1; k <= targets; ++k)
        rows.push_back(targets == 1 ? "visible"
                                    : std::to_string(k) + " of " + std::to_string(targets));
    if (noData)
        rows.emplace_back("no data");
    rows.insert(rows.end(), notes.begin(), notes.end());
    int width = 0;
    for (std::size_t i = 0; i < rows.size(); ++i)
        width = std::max(width, BitmapFont::textWidth(rows[i], fontScale) +
                                    (i >= 1 && i < rows.size() - notes.size() ? swatch + pad : 0));
    const int w = width + 2 * pad, h = pad + int(rows.size()) * (th + pad / 2) + pad / 2;
    const auto at = inCorner(image, corner, w, h, pad);
    const int x0 = at[0], y0 = at[1], x1 = x0 + w, y1 = y0 + h;
    layout.legendBox = {x0, y0, x1, y1};
    fill(image, x0, y0, x1, y1, kWhite);
    const double flat = greyOf(std::sin(std::numbers::pi / 4.0));  // flat ground, sun at 45°
    int y = y0 + pad;
    for (std::size_t i = 0; i < rows.size(); ++i, y += th + pad / 2) {
        int x = x0 + pad;
        const bool isSwatch = i >= 1 && i < rows.size() - notes.size();
        if (isSwatch) {
            const int k = int(i) - 1;  // 0 = not visible; targets + 1 = no data
            for (int sy = y; sy < y + swatch; ++sy)
                for (int sx = x; sx < x + swatch; ++sx)
                    put(image, sx, sy,
                        k > targets ? hatch(sx, sy, std::max(1, layout.scale / 2))
                                    : cellColour(flat, k, targets));
            if (k >= 1 && k <= targets)
                layout.swatchCentres.push_back({x + swatch / 2, y + swatch / 2});
            x += swatch + pad;
        }
        text(image, x, y + 1, rows[i], fontScale, kBlack);
    }
}

}  // namespace

std::vector<float> hillshade(const ElevationGrid& grid, double azimuthDeg, double altitudeDeg,
                             double zFactor) {
    const GridGeometry& g = grid.geometry;
    const double az = azimuthDeg * std::numbers::pi / 180.0;
    const double alt = altitudeDeg * std::numbers::pi / 180.0;
    const double sx = std::sin(az) * std::cos(alt), sy = std::cos(az) * std::cos(alt);
    const double sz = std::sin(alt);
    std::vector<float> shade(grid.heights.size(), std::nanf(""));
    for (int row = 0; row < g.height; ++row) {
        for (int col = 0; col < g.width; ++col) {
            const double centre = grid.at(col, row);
            if (std::isnan(centre))
                continue;
            auto z = [&](int dc, int dr) {
                const int c = col + dc, r = row + dr;
                if (c < 0 || r < 0 || c >= g.width || r >= g.height)
                    return centre * zFactor;
                const double v = grid.at(c, r);
                return (std::isnan(v) ? centre : v) * zFactor;
            };
            const double dzdx =
                ((z(1, -1) + 2 * z(1, 0) + z(1, 1)) - (z(-1, -1) + 2 * z(-1, 0) + z(-1, 1))) /
                (8.0 * g.cellWidth);
            const double dzdy =
                ((z(-1, -1) + 2 * z(0, -1) + z(1, -1)) - (z(-1, 1) + 2 * z(0, 1) + z(1, 1))) /
                (8.0 * g.cellHeight);
            const double norm = std::sqrt(dzdx * dzdx + dzdy * dzdy + 1.0);
            const double lit = (-dzdx * sx - dzdy * sy + sz) / norm;
            shade[std::size_t(row) * g.width + col] = float(std::max(0.0, lit));
        }
    }
    return shade;
}

std::array<std::uint8_t, 3> ztvCountColour(int count, int targets) {
    SYLVA_CHECK(count >= 1 && count <= targets);
    if (targets == 1)
        return {240, 90, 20};
    static constexpr Rgb kStops[] = {{255, 230, 130}, {254, 178, 76}, {240, 59, 32}, {150, 0, 38}};
    const double t = double(count - 1) / double(targets - 1) * 3.0;
    const int i = std::min(int(t), 2);
    const double f = t - i;
    Rgb out;
    for (int c = 0; c < 3; ++c)
        out[c] = std::uint8_t(std::lround(kStops[i][c] * (1 - f) + kStops[i + 1][c] * f));
    return out;
}

namespace {

// The round distance (1, 2 or 5 × 10^k metres) nearest above 0.75 × `target`.
double roundDistance(double target) {
    target = std::max(target, 0.1);
    double spacing = std::pow(10.0, std::floor(std::log10(target)));
    for (double step : {1.0, 2.0, 5.0, 10.0})
        if (spacing * step >= target * 0.75) {
            return spacing * step;
        }
    return spacing * 10.0;
}

}  // namespace

double ringSpacing(double maxDistance) {
    return roundDistance(maxDistance / 6.0);
}

void drawNorthArrow(RgbaImage& image, int x, int y, int size, int fontScale) {
    for (int row = 0; row < 2 * size; ++row) {
        const int half = row / 3;
        for (int col = x - half; col <= x + half; ++col)
            if (col >= 0 && col < image.width && y + row >= 0 && y + row < image.height) {
                std::uint8_t* p = image.at(col, y + row);
                p[0] = p[1] = p[2] = 20;
            }
    }
    BitmapFont::draw(image, x - BitmapFont::textWidth("N", fontScale) / 2, y + 2 * size + 2, "N",
                     fontScale, kBlack.data(), kWhite.data());
}

ZtvMap drawZtvMap(const ElevationGrid& grid, const ViewshedResult& result,
                  std::span<const ViewshedTarget> targets, const ZtvMapOptions& options) {
    const GridGeometry& g = grid.geometry;
    SYLVA_CHECK(result.cells() == grid.heights.size() && g.width > 0 && g.height > 0);
    ZtvMap map;
    int scale = options.scale;
    if (scale <= 0)
        scale = std::clamp((800 + std::max(g.width, g.height) - 1) / std::max(g.width, g.height), 1,
                           16);
    map.layout.scale = scale;
    map.image = RgbaImage(g.width * scale, g.height * scale);
    const int fontScale = std::max(map.image.width, map.image.height) >= 700 ? 2 : 1;
    map.layout.zFactor = options.zFactor > 0.0
                             ? options.zFactor
                             : std::clamp(std::round(g.cellWidth / 30.0), 1.0, 5.0);
    const std::vector<float> shade = hillshade(grid, 315.0, 45.0, map.layout.zFactor);
    drawCells(map.image, shade, result, int(targets.size()), scale);
    const Frame frame{g, scale};
    // The legend in the corner opposite the first target, the scale bar on the target's
    // side (top or bottom) at the other end, so neither hides the target.
    Corner legend{true, true}, bar{true, false};
    if (!targets.empty()) {
        const bool right = frame.px(targets[0].x) > map.image.width / 2.0;
        const bool bottom = frame.py(targets[0].y) > map.image.height / 2.0;
        legend = {!right, !bottom};
        bar = {!right, bottom};
        map.layout.ringSpacing = ringSpacing(farthestCorner(g, targets[0]));
        drawRingLines(map.image, frame, targets, map.layout.ringSpacing);
        // The north arrow in the free corner on the target's side, away from the bar.
        const int arrow = 10 * fontScale;
        drawNorthArrow(map.image, right ? map.image.width - 3 * arrow : 2 * arrow,
                       bottom ? arrow : map.image.height - 5 * arrow, arrow, fontScale);
    }
    for (std::size_t i = 0; i < targets.size(); ++i) {
        drawTarget(map.image, frame, targets[i], 4 * fontScale);
        if (targets.size() > 1)  // numbered, as the GeoTIFF's count and the summary name them
            BitmapFont::draw(map.image, int(frame.px(targets[i].x)) + 6 * fontScale,
                             int(frame.py(targets[i].y)) - 3 * fontScale, std::to_string(i + 1),
                             fontScale, kBlack.data(), kWhite.data());
    }
    const bool noData = std::any_of(result.fraction.begin(), result.fraction.end(),
                                    [](float v) { return std::isnan(v); });
    drawLegend(map.image, options, int(targets.size()), noData, fontScale, legend, map.layout);
    map.layout.scaleBarBox = drawScaleBar(map.image, frame, fontScale, bar);
    if (!targets.empty())
        drawRingLabels(map.image, frame, targets, map.layout.ringSpacing, fontScale,
                       {map.layout.legendBox, map.layout.scaleBarBox});
    return map;
}

Status writeZtvMap(const std::filesystem::path& path, const ZtvMap& map) {
    return ImageWriter::writeRgba8(path, map.image.width, map.image.height, map.image.pixels);
}

}  // namespace sylva
