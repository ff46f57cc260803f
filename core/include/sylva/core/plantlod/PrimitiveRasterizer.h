// PrimitiveRasterizer: the software renderer behind every image error of the plant LoD
// builder (seed 001 §3.3.3, §3.4, §3.5). It draws exactly what the vegetation renderer
// draws (seed 001 §6.4): ray-cast ellipsoids with the EllipsoidNoise alpha test (front
// hit, then back hit when the front is perforated), lines as tapered capsules, and the
// source mesh with alpha-tested leaves, into a luminance + depth buffer.
//
// Views: orthographic, looking at the plant's bounding sphere from `viewCount`
// directions — 3/4 of them around the plant 10° above the horizon, the rest 55° above —
// each image exactly covering the sphere. Orthographic because the error matters for
// distant plants, where perspective is negligible, and it makes the pixel size one
// number (metres per pixel) that maps to the LoD error of seed 001 §6.3.
// Resolution: default 128² resolved from 256² (2 × 2 supersampling). 128 px across a
// plant is where LoD switches to the mesh in practice (a few hundred pixels), gives the
// metric 8 scales, and keeps one full evaluation of a 7k-ellipsoid level at a few ms.
//
// Pixel values: linear luminance of the surface albedo, background 0. Lines thinner
// than a render pixel are drawn one pixel wide with their coverage as opacity, so twigs
// keep their energy instead of flickering in and out.
//
// Thread safety: const methods may be called concurrently on different frames.
#pragma once

#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "sylva/core/plantlod/PlantLod.h"
#include "sylva/core/plantlod/PlantModel.h"

namespace sylva {

struct PixelRect {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // [x0, x1) × [y0, y1), render pixels
    bool empty() const { return x0 >= x1 || y0 >= y1; }
};

// A rectangle of the render image (the full image or a tile of it); pixel (x, y) is at
// value[(y - rect.y0) * width + (x - rect.x0)].
struct RasterFrame {
    PixelRect rect;
    int width() const { return rect.x1 - rect.x0; }
    std::vector<float> value;
    std::vector<float> depth;  // metres along the view direction; +inf = background
};

// Overrides used while calibrating (seed 001 §3.3.3): radii × scale, and a shared alpha
// threshold (< 0: each ellipsoid's own).
struct EllipsoidStyle {
    float scale = 1.0f;
    float alphaThreshold = -1.0f;
};

class PrimitiveRasterizer {
public:
    PrimitiveRasterizer(const glm::vec3& boundsMinimum, const glm::vec3& boundsMaximum,
                        int resolution = 128, int viewCount = 8, int supersampling = 2);

    int resolution() const { return resolution_; }
    int renderSize() const { return resolution_ * supersampling_; }
    int viewCount() const { return static_cast<int>(views_.size()); }
    float renderPixelSize() const { return 2.0f * radius_ / static_cast<float>(renderSize()); }
    // Metres per resolved pixel.
    float pixelSize() const { return 2.0f * radius_ / static_cast<float>(resolution_); }

    RasterFrame blankFrame() const { return blankFrame(fullRect()); }
    RasterFrame blankFrame(const PixelRect& rect) const;
    // Makes `frame` a blank full frame, reusing its storage (calibration renders
    // thousands of frames; allocating them dominated the cost).
    void clearFrame(RasterFrame& frame) const;
    PixelRect fullRect() const { return {0, 0, renderSize(), renderSize()}; }

    void drawEllipsoids(std::span<const LodEllipsoid> ellipsoids, int view, RasterFrame& frame,
                        const EllipsoidStyle& style = {}) const;
    void drawLines(std::span<const LodLine> lines, int view, RasterFrame& frame,
                   float widthScale = 1.0f) const;
    void drawLine(const LodLine& line, int view, RasterFrame& frame, float widthScale = 1.0f) const;
    // Meshes of `part` (or all meshes when includeAll).
    void drawMesh(const PlantModel& model, PlantPart part, bool includeAll, int view,
                  RasterFrame& frame) const;

    // Render pixels a line may touch in a view (clamped to the frame).
    PixelRect lineBounds(const LodLine& line, int view, float widthScale = 1.0f) const;

    // Box-filters the supersampled values of a full frame to resolution².
    std::vector<float> resolve(const RasterFrame& frame) const;

private:
    struct View {
        glm::vec3 right, up, forward;
    };
    glm::vec3 toView(const glm::vec3& p, int view) const;

    std::vector<View> views_;
    glm::vec3 center_{0.0f};
    float radius_ = 1.0f;
    int resolution_ = 128;
    int supersampling_ = 2;
};

}  // namespace sylva
