#include "sylva/core/image/RankFilter.h"

#include <algorithm>
#include <cstddef>

#include "sylva/core/base/Check.h"

namespace sylva {
namespace {

// One line of `count` texels `stride` apart from `in` into `out` (same layout): each
// output texel the extremum of the 2r+1 input texels centred on it, edges clamped.
// `padded`, `forward` and `backward` are scratch of count + 2r texels.
template <typename Op>
void filterLine(const float* in, float* out, int count, std::size_t stride, int r, Op op,
                std::vector<float>& padded, std::vector<float>& forward,
                std::vector<float>& backward) {
    const int length = count + 2 * r;
    const int window = 2 * r + 1;
    for (int i = 0; i < length; ++i) {
        padded[std::size_t(i)] = in[std::size_t(std::clamp(i - r, 0, count - 1)) * stride];
    }
    for (int i = 0; i < length; ++i) {
        forward[std::size_t(i)] = i % window == 0
                                      ? padded[std::size_t(i)]
                                      : op(forward[std::size_t(i - 1)], padded[std::size_t(i)]);
    }
    for (int i = length - 1; i >= 0; --i) {
        backward[std::size_t(i)] = (i + 1) % window == 0 || i == length - 1
                                       ? padded[std::size_t(i)]
                                       : op(backward[std::size_t(i + 1)], padded[std::size_t(i)]);
    }
    // The window of output x is padded[x .. x + 2r]: x's block from x to its end (h) and
    // the next block from its start to x + 2r (g); one block when x starts a block.
    for (int x = 0; x < count; ++x) {
        out[std::size_t(x) * stride] =
            op(backward[std::size_t(x)], forward[std::size_t(x + 2 * r)]);
    }
}

template <typename Op>
void filter(std::vector<float>& grid, int width, int r, Op op) {
    std::vector<float> tmp(grid.size());
    const std::size_t length = std::size_t(width) + 2 * std::size_t(r);
    std::vector<float> padded(length), forward(length), backward(length);
    const std::size_t w = std::size_t(width);
    for (std::size_t y = 0; y < w; ++y) {  // rows
        filterLine(grid.data() + y * w, tmp.data() + y * w, width, 1, r, op, padded, forward,
                   backward);
    }
    for (std::size_t x = 0; x < w; ++x) {  // columns
        filterLine(tmp.data() + x, grid.data() + x, width, w, r, op, padded, forward, backward);
    }
}

}  // namespace

void RankFilter::apply(std::vector<float>& grid, int width, int r, bool dilate) {
    SYLVA_CHECK(width >= 0 && grid.size() == std::size_t(width) * std::size_t(width));
    if (r <= 0 || width == 0) {
        return;
    }
    if (dilate) {
        filter(grid, width, r, [](float a, float b) { return std::max(a, b); });
    } else {
        filter(grid, width, r, [](float a, float b) { return std::min(a, b); });
    }
}

}  // namespace sylva
