#include "sylva/core/plantlod/ImageErrorMetric.h"

#include <bit>
#include <cmath>
#include <cstdint>

#include "sylva/core/base/Check.h"

namespace sylva {

namespace {

int levelCount(int size) {
    SYLVA_CHECK(size > 0 && std::has_single_bit(static_cast<unsigned>(size)));
    return std::countr_zero(static_cast<unsigned>(size)) + 1;
}

// De-interleaves the even bits of a Morton index.
std::uint32_t compactBits(std::uint32_t x) {
    x &= 0x55555555u;
    x = (x | (x >> 1)) & 0x33333333u;
    x = (x | (x >> 2)) & 0x0F0F0F0Fu;
    x = (x | (x >> 4)) & 0x00FF00FFu;
    x = (x | (x >> 8)) & 0x0000FFFFu;
    return x;
}

}  // namespace

std::vector<double> multiScaleSquaredErrors(std::span<const float> sample,
                                            std::span<const float> reference, int size) {
    const int levels = levelCount(size);
    SYLVA_CHECK(sample.size() == reference.size() &&
                sample.size() == static_cast<std::size_t>(size) * size);
    std::vector<double> partial(levels + 1, 0.0);
    std::vector<double> squared(levels, 0.0);
    std::vector<double> inverseBlockPixels(levels);
    for (int k = 0; k < levels; ++k) {
        inverseBlockPixels[k] = std::ldexp(1.0, -2 * k);  // exact: powers of two
    }
    const std::uint32_t pixels =
        static_cast<std::uint32_t>(size) * static_cast<std::uint32_t>(size);
    // The Z-curve order of this size, computed once per thread.
    thread_local std::vector<std::uint32_t> order;
    if (order.size() != pixels) {
        order.resize(pixels);
        for (std::uint32_t i = 0; i < pixels; ++i) {
            order[i] = compactBits(i >> 1) * static_cast<std::uint32_t>(size) + compactBits(i);
        }
    }
    for (std::uint32_t i = 0; i < pixels; ++i) {
        const std::size_t at = order[i];
        partial[0] = static_cast<double>(sample[at]) - static_cast<double>(reference[at]);
        // A block of level k ends where the low 2k bits of i + 1 wrap to zero.
        std::uint32_t next = i + 1;
        for (int k = 0; k < levels; ++k) {
            if (k > 0 && (next & ((1u << (2 * k)) - 1u)) != 0) {
                break;
            }
            const double mean = partial[k] * inverseBlockPixels[k];
            squared[k] += mean * mean;
            partial[k + 1] += partial[k];
            partial[k] = 0.0;
        }
    }
    for (int k = 0; k < levels; ++k) {
        squared[k] /= std::ldexp(1.0, 2 * (levels - 1 - k));  // blocks on level k
    }
    return squared;
}

std::vector<double> multiScaleSquaredErrorsDirect(std::span<const float> sample,
                                                  std::span<const float> reference, int size) {
    const int levels = levelCount(size);
    SYLVA_CHECK(sample.size() == reference.size() &&
                sample.size() == static_cast<std::size_t>(size) * size);
    std::vector<double> difference(sample.size());
    for (std::size_t i = 0; i < sample.size(); ++i) {
        difference[i] = static_cast<double>(sample[i]) - static_cast<double>(reference[i]);
    }
    std::vector<double> squared;
    for (int k = 0, width = size; k < levels; ++k, width /= 2) {
        double sum = 0.0;
        for (double d : difference) {
            sum += d * d;
        }
        squared.push_back(sum / (static_cast<double>(width) * width));
        if (width > 1) {
            std::vector<double> half(static_cast<std::size_t>(width / 2) * (width / 2));
            for (int y = 0; y < width / 2; ++y) {
                for (int x = 0; x < width / 2; ++x) {
                    half[y * (width / 2) + x] =
                        0.25 * (difference[(2 * y) * width + 2 * x] +
                                difference[(2 * y) * width + 2 * x + 1] +
                                difference[(2 * y + 1) * width + 2 * x] +
                                difference[(2 * y + 1) * width + 2 * x + 1]);
                }
            }
            difference = std::move(half);
        }
    }
    return squared;
}

double multiScaleRmse(const std::vector<double>& levelSquaredErrors) {
    if (levelSquaredErrors.empty()) {
        return 0.0;
    }
    double sum = 0.0;
    for (double e : levelSquaredErrors) {
        sum += std::sqrt(e);
    }
    return sum / static_cast<double>(levelSquaredErrors.size());
}

std::vector<double> meanOverViews(const std::vector<std::vector<double>>& perView) {
    SYLVA_CHECK(!perView.empty());
    const int views = static_cast<int>(perView.size());
    std::vector<double> mean(perView[0].size(), 0.0);
    for (const std::vector<double>& levels : perView) {
        SYLVA_CHECK(levels.size() == mean.size());
        for (std::size_t k = 0; k < levels.size(); ++k) {
            mean[k] += levels[k] / views;
        }
    }
    return mean;
}

}  // namespace sylva
