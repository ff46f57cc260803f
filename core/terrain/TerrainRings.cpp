#include "sylva/core/terrain/TerrainRings.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "sylva/core/base/Check.h"

namespace sylva {

TerrainRings::TerrainRings(int columns, int ringsPerLevel)
    : columns_(columns), ringsPerLevel_(ringsPerLevel) {
    SYLVA_CHECK(columns >= 8 && ringsPerLevel >= 2);
    addRows(ring_, 0, ringsPerLevel_, true);
    // The fill disk: two more levels' worth of rings, then a fan to the nadir.
    addRows(fill_, ringsPerLevel_, 3 * ringsPerLevel_, false);
    const auto centre = static_cast<std::uint32_t>(fill_.vertices.size());
    fill_.vertices.push_back({0.0f, 0.0f, 0.0f, 1.0f, 0.0f});
    const auto lastRow = static_cast<std::uint32_t>(centre - (columns_ + 1));
    for (int c = 0; c < columns_; ++c) {
        fill_.indices.insert(fill_.indices.end(), {lastRow + c, centre, lastRow + c + 1});
    }
}

void TerrainRings::addRows(TerrainMesh& mesh, int firstRow, int lastRow, bool blend) const {
    const auto base = static_cast<std::uint32_t>(mesh.vertices.size());
    const float pi = static_cast<float>(std::numbers::pi);
    for (int row = firstRow; row <= lastRow; ++row) {
        float angle =
            static_cast<float>(std::numbers::pi * std::exp2(-double(row) / ringsPerLevel_));
        // Level borders must be exact powers of two of pi in float: the inner border
        // of level i is then bit-identical to the outer border of level i + 1.
        if (row % ringsPerLevel_ == 0) {
            angle = std::ldexp(pi, -row / ringsPerLevel_);
        }
        float weight = 0.0f;
        if (blend) {
            const float u = float(row - firstRow) / ringsPerLevel_;
            const float t = std::clamp((u - kBlendStart) / (kBlendEnd - kBlendStart), 0.0f, 1.0f);
            weight = 1.0f - t * t * (3.0f - 2.0f * t);
        }
        for (int column = 0; column <= columns_; ++column) {
            const double bearing = 2.0 * std::numbers::pi * (column % columns_) / columns_;
            const float seam = column == 0 ? 1.0f : (column == columns_ ? -1.0f : 0.0f);
            mesh.vertices.push_back({angle, weight, static_cast<float>(std::sin(bearing)),
                                     static_cast<float>(std::cos(bearing)), seam});
        }
    }
    const std::uint32_t stride = columns_ + 1;
    for (int row = 0; row < lastRow - firstRow; ++row) {
        for (int column = 0; column < columns_; ++column) {
            const std::uint32_t a = base + row * stride + column;  // outer ring
            const std::uint32_t b = a + stride;                    // inner ring
            mesh.indices.insert(mesh.indices.end(), {a, b, b + 1, a, b + 1, a + 1});
        }
    }
}

}  // namespace sylva
