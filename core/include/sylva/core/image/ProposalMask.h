// ProposalMask: the per-pixel masks of a photomontage and its wirelines (issue 18; LI TGN
// 06/19 Types 2 and 3), from two renders of one camera: the baseline scenario (what the
// photograph shows) and the proposed scenario (the baseline plus the proposal). Both come
// as reversed-Z depth buffers (SceneRenderer::depth: depth = near / distance along the
// view axis, 0 where nothing is drawn, i.e. sky; rows top to bottom, width × height).
//
// A pixel belongs to the proposal where the proposed scenario's surface is nearer than
// the baseline's: the proposal's own surfaces, minus every part the terrain, plants and
// buildings of the baseline hide (they are drawn in both renders, at the same depth).
// Comparing depths rather than colours keeps shadows, haze and plants' noise out of the
// mask. Masks are one byte per pixel, 1 inside, 0 outside. Buffer sizes that do not
// match width × height are programmer errors (SYLVA_CHECK).
#pragma once

#include <cstdint>
#include <vector>

namespace sylva {

using PixelMask = std::vector<std::uint8_t>;

class ProposalMask {
public:
    // Relative distance by which the proposed surface must be nearer (0.001: 1 m at 1 km):
    // above float depth noise, below any wall standing on the ground it is seen against.
    static constexpr double kDefaultTolerance = 0.001;

    // The proposal's visible pixels.
    static PixelMask fromDepths(const std::vector<float>& baseline,
                                const std::vector<float>& proposed, int width, int height,
                                double tolerance = kDefaultTolerance);
    // The silhouette of `mask`: its pixels with a 4-neighbour outside it (the image's own
    // edges are not part of a silhouette). The outline of the visible proposal, occlusion
    // edges included (AVR1: the degree of visibility).
    static PixelMask outline(const PixelMask& mask, int width, int height);
    // The skyline of a render: drawn pixels (depth > 0) whose upper neighbour is sky.
    static PixelMask skyline(const std::vector<float>& depth, int width, int height);
    // Pixels set in `mask`.
    static std::size_t count(const PixelMask& mask);
};

}  // namespace sylva
