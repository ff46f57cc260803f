#include "sylva/core/image/ProposalMask.h"

#include <algorithm>

#include "sylva/core/base/Check.h"

namespace sylva {

PixelMask ProposalMask::fromDepths(const std::vector<float>& baseline,
                                   const std::vector<float>& proposed, int width, int height,
                                   double tolerance) {
    const std::size_t size = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    SYLVA_CHECK(baseline.size() == size && proposed.size() == size);
    SYLVA_CHECK(tolerance >= 0.0 && tolerance < 1.0);
    PixelMask mask(size, 0);
    // distance = near / depth, so "nearer by the fraction t" is
    // near / proposed < (1 − t) · near / baseline  ⇔  proposed · (1 − t) > baseline.
    const double keep = 1.0 - tolerance;
    for (std::size_t i = 0; i < size; ++i) {
        mask[i] = proposed[i] > 0.0f && double(proposed[i]) * keep > double(baseline[i]) ? 1 : 0;
    }
    return mask;
}

PixelMask ProposalMask::outline(const PixelMask& mask, int width, int height) {
    const std::size_t size = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    SYLVA_CHECK(mask.size() == size);
    PixelMask lines(size, 0);
    auto outside = [&](int x, int y) {
        return x >= 0 && x < width && y >= 0 && y < height &&
               mask[static_cast<std::size_t>(y) * width + x] == 0;
    };
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const std::size_t i = static_cast<std::size_t>(y) * width + x;
            if (mask[i] != 0 && (outside(x - 1, y) || outside(x + 1, y) || outside(x, y - 1) ||
                                 outside(x, y + 1))) {
                lines[i] = 1;
            }
        }
    }
    return lines;
}

PixelMask ProposalMask::skyline(const std::vector<float>& depth, int width, int height) {
    const std::size_t size = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
    SYLVA_CHECK(depth.size() == size);
    PixelMask lines(size, 0);
    for (int y = 1; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const std::size_t i = static_cast<std::size_t>(y) * width + x;
            if (depth[i] > 0.0f && depth[i - static_cast<std::size_t>(width)] == 0.0f) {
                lines[i] = 1;
            }
        }
    }
    return lines;
}

std::size_t ProposalMask::count(const PixelMask& mask) {
    return static_cast<std::size_t>(
        std::count_if(mask.begin(), mask.end(), [](std::uint8_t v) { return v != 0; }));
}

}  // namespace sylva
