// DepthPyramid: a hierarchical-Z buffer on the CPU (Greene, Kass & Miller 1993) for
// occlusion culling of plant instances and instance tiles (issue 21 item 2). Built from a
// depth image the renderer reads back (the terrain pass, then the nearer plants of the
// same frame); level 0 is that image, every further level keeps the farthest depth of
// each 2×2 block below it. A bounding sphere is hidden when its nearest point lies behind
// the farthest depth of every pixel its screen rectangle may cover: then no fragment of
// anything inside the sphere can pass the renderer's depth test (GREATER, reversed-Z).
//
// Depth convention: reversed-Z as the SceneRenderer's projection writes it, depth =
// near / axial distance (metres along the view axis), 0 = infinitely far. The projection
// is the symmetric-or-lens-shifted perspective of SceneRenderer::projection (ndc.x =
// p00 · x / -z − p20, ndc.y = p11 · y / -z − p21); view space looks down −Z, metres.
//
// The test is conservative: the screen rectangle is the exact extent of the sphere's
// perspective image (tangent planes through the view axes) widened by one pixel, and the
// sphere's depth must be behind the stored depth by a relative margin (kDepthMargin).
// CPU only; building is O(pixels), a test reads at most 4×4 texels of one level.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

namespace sylva {

class DepthPyramid {
public:
    // Relative depth margin: a sphere counts as hidden only when its nearest depth is
    // smaller than the stored farthest depth by this fraction (float depth rounding).
    static constexpr float kDepthMargin = 1e-4f;

    // Builds the pyramid of a width × height depth image, rows bottom to top (as
    // glReadPixels returns them). `projection` is the column-major perspective matrix the
    // image was drawn with (only p00, p11, p20, p21 are read); `near` in metres. A size
    // below 1 or a depth count other than width × height leaves the pyramid empty (then
    // nothing is hidden).
    void build(std::span<const float> depth, int width, int height, const glm::dmat4& projection,
               double near);
    void clear();
    bool empty() const { return levels_.empty(); }
    int width() const { return empty() ? 0 : levels_[0].width; }
    int height() const { return empty() ? 0 : levels_[0].height; }

    // Whether a sphere (centre in view space, radius in metres) is wholly hidden behind
    // the stored depths. False for an empty pyramid and for spheres reaching the near
    // plane; true for spheres whose rectangle misses the image.
    bool hidden(const glm::vec3& center, float radius) const;

    // The farthest (smallest) depth over pixels [x0, x1] × [y0, y1] (inclusive, rows from
    // the bottom, clamped to the image), read from the coarsest level that spans the
    // rectangle with at most 4 × 4 texels (so it may include pixels just outside it).
    float farthestDepth(int x0, int y0, int x1, int y1) const;

private:
    struct Level {
        int width = 0, height = 0;
        std::vector<float> depth;  // rows bottom to top
    };
    std::vector<Level> levels_;
    double near_ = 0.0;
    // Pixel coordinates (x from the left, y from the bottom) of a view direction with
    // tangents (tx, ty) = (x / -z, y / -z): pixel = scale * tangent + offset.
    glm::dvec2 scale_{0.0}, offset_{0.0};
};

}  // namespace sylva
