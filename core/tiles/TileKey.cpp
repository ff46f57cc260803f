#include "sylva/core/tiles/TileKey.h"

#include <cstdio>
#include <numbers>

namespace sylva {

bool TileKey::valid() const {
    return level >= 0 && level <= kMaxLevel && lonReduction >= 0 && lonReduction <= level + 1 &&
           x >= 0 && x < columns() && y >= 0 && y < rows();
}

double TileKey::west() const {
    return -std::numbers::pi + 2.0 * std::numbers::pi * x / columns();
}
double TileKey::east() const {
    return -std::numbers::pi + 2.0 * std::numbers::pi * (x + 1) / columns();
}
double TileKey::north() const {
    return std::numbers::pi / 2 - std::numbers::pi * y / rows();
}
double TileKey::south() const {
    return std::numbers::pi / 2 - std::numbers::pi * (y + 1) / rows();
}

TileKey TileKey::parent() const {
    TileKey result = *this;
    if (level == 0) {
        return result;
    }
    result.level = level - 1;
    result.lonReduction = lonReduction > result.level + 1 ? result.level + 1 : lonReduction;
    // Columns halve when the level drops, unless the reduction had to shrink too.
    const int shift = 1 - (lonReduction - result.lonReduction);
    result.x = x >> shift;
    result.y = y >> 1;
    return result;
}

std::string TileKey::toString() const {
    // snprintf rather than string concatenation: GCC 12 warns falsely (-Wrestrict) on
    // "literal" + std::string chains.
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "L%d/k%d/x%d/y%d", level, lonReduction, x, y);
    return buffer;
}

}  // namespace sylva
