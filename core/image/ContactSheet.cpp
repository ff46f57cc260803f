#include "sylva/core/image/ContactSheet.h"

#include <algorithm>
#include <cmath>

#include "sylva/core/image/BitmapFont.h"
#include "sylva/core/image/ColorSpace.h"

namespace sylva {

RgbaImage ContactSheet::resize(const RgbaImage& image, int width, int height) {
    SYLVA_CHECK(width > 0 && height > 0 && image.width > 0 && image.height > 0);
    RgbaImage out(width, height);
    const double sx = static_cast<double>(image.width) / width;
    const double sy = static_cast<double>(image.height) / height;
    for (int y = 0; y < height; ++y) {
        const double y0 = y * sy;
        const double y1 = (y + 1) * sy;
        for (int x = 0; x < width; ++x) {
            const double x0 = x * sx;
            const double x1 = (x + 1) * sx;
            double sum[4] = {0, 0, 0, 0};
            double weightSum = 0;
            for (int iy = static_cast<int>(y0);
                 iy < std::min(image.height, static_cast<int>(std::ceil(y1))); ++iy) {
                const double wy = std::min<double>(iy + 1, y1) - std::max<double>(iy, y0);
                for (int ix = static_cast<int>(x0);
                     ix < std::min(image.width, static_cast<int>(std::ceil(x1))); ++ix) {
                    const double w = wy * (std::min<double>(ix + 1, x1) - std::max<double>(ix, x0));
                    const std::uint8_t* p = image.at(ix, iy);
                    for (int c = 0; c < 3; ++c) {
                        sum[c] += w * srgbToLinear(p[c] / 255.0f);
                    }
                    sum[3] += w * p[3];
                    weightSum += w;
                }
            }
            std::uint8_t* q = out.at(x, y);
            for (int c = 0; c < 3; ++c) {
                q[c] = static_cast<std::uint8_t>(std::lround(
                    std::clamp(linearToSrgb(static_cast<float>(sum[c] / weightSum)), 0.0f, 1.0f) *
                    255));
            }
            q[3] = static_cast<std::uint8_t>(std::lround(sum[3] / weightSum));
        }
    }
    return out;
}

Result<RgbaImage> ContactSheet::build(const std::vector<ContactSheetEntry>& entries,
                                      int thumbnailWidth, int columns) {
    if (entries.empty()) {
        return Error{"a contact sheet needs at least one image"};
    }
    if (thumbnailWidth < 16) {
        return Error{"contact sheet thumbnails must be at least 16 pixels wide"};
    }
    const int count = static_cast<int>(entries.size());
    if (columns <= 0) {
        columns = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(count))));
    }
    const int rows = (count + columns - 1) / columns;
    int thumbnailHeight = 0;
    for (const ContactSheetEntry& entry : entries) {
        if (entry.image.width <= 0 || entry.image.height <= 0) {
            return Error{"contact sheet image '" + entry.label + "' is empty"};
        }
        thumbnailHeight = std::max(
            thumbnailHeight, static_cast<int>(std::lround(static_cast<double>(thumbnailWidth) *
                                                          entry.image.height / entry.image.width)));
    }
    const int scale = 1;
    const int gap = 8;
    const int labelHeight = BitmapFont::textHeight(scale) + 4;
    const int cellWidth = thumbnailWidth + gap;
    const int cellHeight = thumbnailHeight + labelHeight + gap;
    RgbaImage sheet(columns * cellWidth + gap, rows * cellHeight + gap, 28, 28, 28);
    const std::uint8_t text[3] = {230, 230, 230};
    for (int i = 0; i < count; ++i) {
        const ContactSheetEntry& entry = entries[static_cast<std::size_t>(i)];
        const int x = gap + (i % columns) * cellWidth;
        const int y = gap + (i / columns) * cellHeight;
        const int height =
            std::max(1, static_cast<int>(std::lround(static_cast<double>(thumbnailWidth) *
                                                     entry.image.height / entry.image.width)));
        const RgbaImage thumbnail = resize(entry.image, thumbnailWidth, height);
        copyPixels(thumbnail, 0, 0, thumbnail.width, thumbnail.height, sheet, x, y);
        // Labels longer than the thumbnail are cut with an ellipsis.
        std::string caption = entry.label;
        const std::size_t fits =
            static_cast<std::size_t>(thumbnailWidth / (BitmapFont::kCellWidth * scale));
        if (caption.size() > fits && fits > 3) {
            caption = caption.substr(0, fits - 3) + "...";
        }
        BitmapFont::draw(sheet, x, y + thumbnailHeight + 3, caption, scale, text);
    }
    return sheet;
}

}  // namespace sylva
