// ImageErrorMetric: multi-scale RMSE between two square single-channel images (seed 001
// §3.5). Level k compares the images box-filtered to (size / 2^k)², i.e. it measures the
// RMS of the difference image averaged over 2^k × 2^k blocks; the metric is the mean of
// the per-level RMS values over all levels down to 1 × 1, so both single-pixel and
// large-scale differences count.
//
// The thesis evaluates all levels in one pass by scanning the difference image along a
// Z (Morton) curve: every block of every level is a contiguous run of that scan, so one
// running sum per level suffices (log2(size) + 1 values). `multiScaleSquaredErrors` does
// exactly that; `multiScaleSquaredErrorsDirect` builds the mip pyramid level by level and
// exists to test the single pass against.
//
// Images: row-major floats, any linear quantity (the rasterizer writes luminance). The
// size must be a power of two (SYLVA_CHECK: the caller chooses the resolution).
#pragma once

#include <span>
#include <vector>

namespace sylva {

// Per level k = 0 … log2(size): mean over blocks of (mean difference in the block)².
std::vector<double> multiScaleSquaredErrors(std::span<const float> sample,
                                            std::span<const float> reference, int size);
std::vector<double> multiScaleSquaredErrorsDirect(std::span<const float> sample,
                                                  std::span<const float> reference, int size);

// Mean over levels of sqrt(level error).
double multiScaleRmse(const std::vector<double>& levelSquaredErrors);

// Level by level, the mean of the level errors of several views (each view's list from
// multiScaleSquaredErrors, all of one length; at least one view).
std::vector<double> meanOverViews(const std::vector<std::vector<double>>& perView);

}  // namespace sylva
