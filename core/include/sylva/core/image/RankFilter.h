// RankFilter: separable erosion (minimum) or dilation (maximum) of a square float grid
// with a square structuring element of radius r (a (2r+1)² window), edges clamped (the
// window reads the nearest edge texel beyond the grid) — the morphological opening and
// closing of MaskSource (`open`, `close`).
//
// Algorithm: van Herk (1992), "A fast algorithm for local minimum and maximum filters on
// rectangular and octagonal kernels", Pattern Recognition Letters 13(7), and Gil &
// Werman (1993), IEEE PAMI 15(5): each line, padded by r clamped texels per side, is cut
// into blocks of 2r+1; a running extremum forward within each block (g) and one backward
// (h) give every window's extremum as op(h[x], g[x + 2r]) — three comparisons a texel
// whatever r, instead of 2r+1 (at a fine level a 60 m opening is a radius of hundreds of
// texels). The values are exactly those of the direct definition (min and max are exact
// and do not depend on the order of comparison; RankFilterTest compares bit for bit).
#pragma once

#include <vector>

namespace sylva {

class RankFilter {
public:
    // `grid`: width × width texels, row-major; replaced by its erosion (`dilate` false)
    // or dilation. r <= 0 leaves it as it is. Programmer error (checked) when the grid is
    // not width² texels.
    static void apply(std::vector<float>& grid, int width, int r, bool dilate);
};

}  // namespace sylva
