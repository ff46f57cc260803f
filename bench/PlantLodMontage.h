// PlantLodMontage: the picture of `sylva bench plantlod --montage`: one row per plant,
// the source mesh, then every ellipsoid/line level, then every billboard level, each seen
// from the LoD builder's first view (PrimitiveRasterizer, luminance as grey) — exactly
// the images the error metric compares. White background, a grey border per cell.
#pragma once

#include <string>
#include <vector>

#include "sylva/core/base/Result.h"
#include "sylva/core/plantlod/PlantLod.h"
#include "sylva/core/plantlod/PlantModel.h"

namespace sylva::bench {

class PlantLodMontage {
public:
    explicit PlantLodMontage(int cellSize) : cellSize_(cellSize) {}

    void addRow(const PlantModel& model, const PlantLod& lod);
    // An 8-bit sRGB PNG (ImageWriter), rows × the longest row's cells; fails like
    // ImageWriter::writeRgba8.
    Status write(const std::string& path) const;

private:
    int cellSize_;                                       // pixels per side of a cell
    int cells_ = 0;                                      // of the longest row
    std::vector<std::vector<std::vector<float>>> rows_;  // row → cell → luminance
};

}  // namespace sylva::bench
