#include "sylva/core/analysis/ShadowMap.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "sylva/core/analysis/ZtvMap.h"
#include "sylva/core/base/Check.h"
#include "sylva/core/image/BitmapFont.h"
#include "sylva/core/image/ImageWriter.h"

namespace sylva {

namespace {

constexpr double kDegree = 180.0 / 3.14159265358979323846;
constexpr std::uint8_t kWhite[3] = {255, 255, 255};
constexpr std::uint8_t kBlack[3] = {0, 0, 0};

void fillCell(RgbaImage& image, int col, int row, int scale, const double rgb[3]) {
    for (int y = 0; y < scale; ++y)
        for (int x = 0; x < scale; ++x) {
            std::uint8_t* p = image.at(col * scale + x, row * scale + y);
            for (int k = 0; k < 3; ++k)
                p[k] = std::uint8_t(std::clamp(rgb[k], 0.0, 1.0) * 255.0 + 0.5);
            p[3] = 255;
        }
}

bool inSite(const GridGeometry& g, const std::vector<std::uint8_t>& site, int col, int row) {
    return col >= 0 && row >= 0 && col < g.width && row < g.height &&
           site[std::size_t(row) * std::size_t(g.width) + std::size_t(col)] != 0;
}

// The site's outline: the pixels of site cells along an edge shared with a cell outside,
// max(2, scale / 3) pixels wide, in yellow.
void outlineSite(RgbaImage& image, const GridGeometry& g, const std::vector<std::uint8_t>& site,
                 int scale) {
    const int width = std::max(2, scale / 3);
    auto paint = [&](int x0, int y0, int w, int h) {
        for (int y = y0; y < y0 + h; ++y)
            for (int x = x0; x < x0 + w; ++x) {
                std::uint8_t* p = image.at(x, y);
                p[0] = 255;
                p[1] = 220;
                p[2] = 0;
            }
    };
    for (int r = 0; r < g.height; ++r)
        for (int c = 0; c < g.width; ++c) {
            if (!inSite(g, site, c, r))
                continue;
            const int x = c * scale, y = r * scale;
            if (!inSite(g, site, c - 1, r))
                paint(x, y, width, scale);
            if (!inSite(g, site, c + 1, r))
                paint(x + scale - width, y, width, scale);
            if (!inSite(g, site, c, r - 1))
                paint(x, y, scale, width);
            if (!inSite(g, site, c, r + 1))
                paint(x, y + scale - width, scale, width);
        }
}

}  // namespace

int shadowFrameScale(const GridGeometry& grid) {
    const int longer = std::max(grid.width, grid.height);
    return std::clamp((640 + longer - 1) / std::max(longer, 1), 1, 16);
}

RgbaImage drawShadowFrame(const ElevationGrid& ground, const std::vector<float>& screens,
                          const std::vector<std::uint8_t>& site, const ShadowFrame& frame,
                          const std::string& date, int scale) {
    const GridGeometry& g = ground.geometry;
    SYLVA_CHECK(frame.lit.size() == ground.heights.size());
    SYLVA_CHECK(screens.empty() || screens.size() == ground.heights.size());
    SYLVA_CHECK(site.empty() || site.size() == ground.heights.size());
    const double sunAltitude = std::max(frame.elevation * kDegree, 5.0);
    const std::vector<float> shade = hillshade(ground, frame.azimuth * kDegree, sunAltitude, 1.0);
    RgbaImage image(g.width * scale, g.height * scale);
    for (int r = 0; r < g.height; ++r)
        for (int c = 0; c < g.width; ++c) {
            const std::size_t i = std::size_t(r) * std::size_t(g.width) + std::size_t(c);
            const double grey = std::isnan(shade[i]) ? 0.5 : 0.35 + 0.6 * shade[i];
            double rgb[3] = {grey, grey, grey};
            if (!screens.empty() && screens[i] > 0.0f) {
                rgb[0] = 0.62 * grey + 0.25;
                rgb[1] = 0.45 * grey + 0.12;
                rgb[2] = 0.30 * grey + 0.05;
            }
            if (frame.lit[i] == 0) {
                rgb[0] *= 0.40;
                rgb[1] *= 0.42;
                rgb[2] = rgb[2] * 0.45 + 0.12;
            }
            fillCell(image, c, r, scale, rgb);
        }
    if (!site.empty())
        outlineSite(image, g, site, scale);
    char caption[96];
    std::snprintf(caption, sizeof caption, "%s %s  sun %.0f deg up, azimuth %.0f deg", date.c_str(),
                  frame.label.c_str(), frame.elevation * kDegree, frame.azimuth * kDegree);
    BitmapFont::draw(image, 6, 6, caption, 2, kBlack, kWhite);
    const int arrow = std::max(12, image.width / 40);
    drawNorthArrow(image, image.width - 2 * arrow, arrow, arrow, 2);
    return image;
}

RgbaImage drawContactSheet(const std::vector<RgbaImage>& frames,
                           const std::vector<std::string>& captions, int columns,
                           int thumbnailWidth) {
    SYLVA_CHECK(frames.size() == captions.size() && columns > 0 && thumbnailWidth > 0);
    if (frames.empty())
        return RgbaImage(thumbnailWidth, thumbnailWidth, 255, 255, 255);
    const int thumbHeight =
        std::max(1, int(std::lround(double(thumbnailWidth) * frames[0].height / frames[0].width)));
    const int gap = 6, captionHeight = BitmapFont::textHeight(2) + 4;
    const int rows = (int(frames.size()) + columns - 1) / columns;
    RgbaImage sheet(columns * (thumbnailWidth + gap) + gap,
                    rows * (thumbHeight + captionHeight + gap) + gap, 255, 255, 255);
    for (std::size_t f = 0; f < frames.size(); ++f) {
        const int x0 = gap + int(f % std::size_t(columns)) * (thumbnailWidth + gap);
        const int y0 = gap + int(f / std::size_t(columns)) * (thumbHeight + captionHeight + gap);
        const RgbaImage& frame = frames[f];
        for (int y = 0; y < thumbHeight; ++y)
            for (int x = 0; x < thumbnailWidth; ++x) {
                // Box filter over the frame pixels this thumbnail pixel covers.
                const int sx0 = x * frame.width / thumbnailWidth;
                const int sx1 = std::max(sx0 + 1, (x + 1) * frame.width / thumbnailWidth);
                const int sy0 = y * frame.height / thumbHeight;
                const int sy1 = std::max(sy0 + 1, (y + 1) * frame.height / thumbHeight);
                int sum[3] = {0, 0, 0}, n = 0;
                for (int sy = sy0; sy < std::min(sy1, frame.height); ++sy)
                    for (int sx = sx0; sx < std::min(sx1, frame.width); ++sx, ++n)
                        for (int k = 0; k < 3; ++k)
                            sum[k] += frame.at(sx, sy)[k];
                std::uint8_t* p = sheet.at(x0 + x, y0 + y);
                for (int k = 0; k < 3; ++k)
                    p[k] = std::uint8_t(n > 0 ? sum[k] / n : 255);
            }
        BitmapFont::draw(sheet, x0, y0 + thumbHeight + 2, captions[f], 2, kBlack);
    }
    return sheet;
}

Status writeShadowImage(const std::filesystem::path& path, const RgbaImage& image) {
    return ImageWriter::writeRgba8(path, image.width, image.height, image.pixels);
}

}  // namespace sylva
