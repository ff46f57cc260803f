// PlantRasterizer: a small software rasterizer for plant models (previews, montages,
// and later billboard-cloud atlases). Orthographic, z-buffered, alpha-tested like the
// renderer (texel alpha × baseColor.a < alphaCutoff is discarded), Lambert light from
// the upper left plus ambient, both faces lit.
//
// Frame: the model frame (metres, +Z up). The side view looks along +Y: image x is
// model x, image up is model z. Output: RGBA8, rows from the top, sRGB, alpha 0 where
// nothing was drawn.
#pragma once

#include <cstdint>
#include <vector>

#include "sylva/core/base/Check.h"
#include "sylva/core/plantlod/PlantModel.h"

namespace sylva {

struct RasterImage {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> rgba;
};

// An orthographic view: image x runs along `right`, image up along `up` (both unit,
// orthogonal, model frame); the eye looks along −cross(right, up). The image covers
// [minimum, maximum] in (right, up) coordinates relative to `origin`.
struct OrthographicView {
    glm::vec3 origin{0.0f};
    glm::vec3 right{1.0f, 0.0f, 0.0f};
    glm::vec3 up{0.0f, 0.0f, 1.0f};
    glm::vec2 minimum{-1.0f};
    glm::vec2 maximum{1.0f};
    bool lit = true;  // false: unlit albedo (texture bakes)
};

class PlantRasterizer {
public:
    // Renders the triangles of `model` (all, or those whose flag in `triangleMask` is set;
    // the mask is indexed by mesh, then triangle) into width × height pixels.
    static RasterImage renderOrthographic(
        const PlantModel& model, const OrthographicView& view, int width, int height,
        const std::vector<std::vector<bool>>* triangleMask = nullptr);
    // Renders the model's side view fitted into width × height (aspect kept, the
    // base at the bottom with a small margin). width, height > 0 (SYLVA_CHECK).
    static RasterImage renderSide(const PlantModel& model, int width, int height);
};

}  // namespace sylva
