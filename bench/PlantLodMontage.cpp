#include "PlantLodMontage.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "sylva/core/image/ImageWriter.h"
#include "sylva/core/plantlod/BillboardCloudBuilder.h"
#include "sylva/core/plantlod/PrimitiveRasterizer.h"

namespace sylva::bench {

namespace {

// Luminance [0, 1] → grey sRGB-ish byte (square root: dark foliage stays visible).
std::uint8_t greyByte(float value) {
    return static_cast<std::uint8_t>(
        std::lround(255.0f * std::sqrt(std::clamp(value, 0.0f, 1.0f))));
}

// The ellipsoids of level `k` and the lines drawn at its error.
void drawLevel(const PrimitiveRasterizer& rasterizer, const PlantLod& lod, std::size_t k,
               RasterFrame& frame) {
    std::vector<LodEllipsoid> ellipsoids;
    for (const LodEllipsoid& e : lod.ellipsoids) {
        if (e.level == k) {
            ellipsoids.push_back(e);
        }
    }
    std::vector<LodLine> lines;
    const float error = lod.levels[k].errorMinimum;
    for (const LodLine& l : lod.lines) {
        if (l.errorMinimum <= error && error < l.errorMaximum) {
            lines.push_back(l);
        }
    }
    rasterizer.clearFrame(frame);
    rasterizer.drawEllipsoids(ellipsoids, 0, frame);
    rasterizer.drawLines(lines, 0, frame);
}

}  // namespace

void PlantLodMontage::addRow(const PlantModel& model, const PlantLod& lod) {
    const PrimitiveRasterizer rasterizer(lod.boundsMinimum, lod.boundsMaximum, cellSize_, 8, 2);
    std::vector<std::vector<float>> images;
    RasterFrame frame = rasterizer.blankFrame();
    rasterizer.drawMesh(model, PlantPart::Leaf, true, 0, frame);
    images.push_back(rasterizer.resolve(frame));
    for (std::size_t k = 0; k < lod.levels.size(); ++k) {
        drawLevel(rasterizer, lod, k, frame);
        images.push_back(rasterizer.resolve(frame));
    }
    for (const BillboardLevel& level : lod.billboards.levels) {
        rasterizer.clearFrame(frame);
        rasterizer.drawMesh(BillboardCloudBuilder::levelModel(level, model.name), PlantPart::Leaf,
                            true, 0, frame);
        images.push_back(rasterizer.resolve(frame));
    }
    cells_ = std::max(cells_, static_cast<int>(images.size()));
    rows_.push_back(std::move(images));
}

Status PlantLodMontage::write(const std::string& path) const {
    const int size = cellSize_;
    const int width = size * cells_, height = size * static_cast<int>(rows_.size());
    std::vector<std::uint8_t> rgba(static_cast<std::size_t>(width) * height * 4, 255);
    for (std::size_t r = 0; r < rows_.size(); ++r) {
        for (std::size_t c = 0; c < rows_[r].size(); ++c) {
            for (int y = 0; y < size; ++y) {
                for (int x = 0; x < size; ++x) {
                    // Background (0) white, the plant dark on it; a grey border per cell.
                    const float v = rows_[r][c][static_cast<std::size_t>(y) * size + x];
                    const bool border = x == 0 || y == 0;
                    const std::uint8_t g = border ? 160 : v > 0.0f ? greyByte(v) : 255;
                    const std::size_t at =
                        (static_cast<std::size_t>(r * size + y) * width + c * size + x) * 4;
                    rgba[at] = rgba[at + 1] = rgba[at + 2] = g;
                }
            }
        }
    }
    return ImageWriter::writeRgba8(path, width, height, rgba);
}

}  // namespace sylva::bench
