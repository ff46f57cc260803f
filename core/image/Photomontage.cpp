#include "sylva/core/image/Photomontage.h"

#include <cmath>

namespace sylva {

WirelineMasks WirelineMasks::fromDepths(const std::vector<float>& baseline,
                                        const std::vector<float>& proposed, int width, int height) {
    WirelineMasks masks;
    masks.proposal = ProposalMask::fromDepths(baseline, proposed, width, height);
    masks.silhouette = ProposalMask::outline(masks.proposal, width, height);
    masks.skyline = ProposalMask::skyline(baseline, width, height);
    return masks;
}

void Photomontage::drawWireline(RgbaImage& image, const WirelineMasks& masks,
                                const WirelineStyle& style) {
    drawLines(image, masks.skyline, style.skyline, style.width);
    drawLines(image, masks.silhouette, style.silhouette, style.width);
}

RgbaImage Photomontage::composite(const RgbaImage& photo, const RgbaImage& render,
                                  const PixelMask& mask) {
    SYLVA_CHECK(photo.width == render.width && photo.height == render.height);
    SYLVA_CHECK(mask.size() == static_cast<std::size_t>(photo.width) * photo.height);
    RgbaImage out = photo;
    for (std::size_t i = 0; i < mask.size(); ++i) {
        if (mask[i] != 0) {
            for (int c = 0; c < 3; ++c) {
                out.pixels[i * 4 + c] = render.pixels[i * 4 + c];
            }
            out.pixels[i * 4 + 3] = RgbaImage::kOpaque;
        }
    }
    return out;
}

void Photomontage::drawLines(RgbaImage& image, const PixelMask& lines,
                             const std::array<std::uint8_t, 4>& colour, double width) {
    SYLVA_CHECK(lines.size() == static_cast<std::size_t>(image.width) * image.height);
    SYLVA_CHECK(width >= 1.0);
    const double radius = width / 2.0;
    const int reach = static_cast<int>(std::ceil(radius - 0.5));
    const double alpha = colour[3] / 255.0;
    for (int y = 0; y < image.height; ++y) {
        for (int x = 0; x < image.width; ++x) {
            if (lines[static_cast<std::size_t>(y) * image.width + x] == 0) {
                continue;
            }
            for (int dy = -reach; dy <= reach; ++dy) {
                for (int dx = -reach; dx <= reach; ++dx) {
                    const int px = x + dx, py = y + dy;
                    if (px < 0 || py < 0 || px >= image.width || py >= image.height ||
                        dx * dx + dy * dy > (radius + 0.25) * (radius + 0.25)) {
                        continue;
                    }
                    std::uint8_t* pixel = image.at(px, py);
                    for (int c = 0; c < 3; ++c) {
                        pixel[c] = static_cast<std::uint8_t>(
                            std::lround(pixel[c] * (1.0 - alpha) + colour[c] * alpha));
                    }
                }
            }
        }
    }
}

}  // namespace sylva
