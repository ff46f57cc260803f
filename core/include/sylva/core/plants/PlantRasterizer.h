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
#include "sylva/core/plants/PlantModel.h"

namespace sylva {

struct RasterImage {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> rgba;
};

class PlantRasterizer {
public:
    // Renders the model's side view fitted into width × height (aspect kept, the
    // base at the bottom with a small margin). width, height > 0 (SYLVA_CHECK).
    static RasterImage renderSide(const PlantModel& model, int width, int height);
};

}  // namespace sylva
