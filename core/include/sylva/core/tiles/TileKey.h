// TileKey: one tile of the anisotropic longitude/latitude pyramid (seed 001 §4.4.1).
//
// Level 0 splits the map (360° x 180°) into 2 x 1 tiles; each level splits both
// directions. Spherical clipmaps near the poles need tiles that are wider in
// longitude than in latitude (§5.4.1), so a key also carries a longitude reduction
// k: the grid of (level, k) has (2^(level+1) >> k) columns and 2^level rows.
// Column x grows eastwards from -180°, row y grows southwards from the north pole.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>

namespace sylva {

struct TileKey {
    std::int32_t level = 0;         // 0 .. kMaxLevel
    std::int32_t lonReduction = 0;  // k, 0 .. level + 1
    std::int32_t x = 0;             // column, 0 .. columns - 1
    std::int32_t y = 0;             // row, 0 .. rows - 1

    // 2^(level+1) columns must fit an int32: level 29 has texels of ~1 mm at 256².
    static constexpr std::int32_t kMaxLevel = 29;

    std::int32_t columns() const { return columns(level, lonReduction); }
    std::int32_t rows() const { return rows(level); }
    static std::int32_t columns(std::int32_t level, std::int32_t lonReduction) {
        return (std::int32_t{2} << level) >> lonReduction;
    }
    static std::int32_t rows(std::int32_t level) { return std::int32_t{1} << level; }
    bool valid() const;

    // Bounds in radians: west/east longitude in [-pi, pi], north/south latitude.
    double west() const;
    double east() const;
    double north() const;
    double south() const;

    // The tile of the next coarser level (same lonReduction where possible) that
    // contains this one.
    TileKey parent() const;

    std::string toString() const;  // "L5/k1/x12/y7"

    friend bool operator==(const TileKey&, const TileKey&) = default;
    friend auto operator<=>(const TileKey&, const TileKey&) = default;
};

struct TileKeyHash {
    std::size_t operator()(const TileKey& key) const {
        std::uint64_t h = static_cast<std::uint64_t>(key.level) * 0x9E3779B97F4A7C15ull;
        h ^= static_cast<std::uint64_t>(key.lonReduction) + 0x632BE59BD9B4E019ull + (h << 6) +
             (h >> 2);
        h ^= static_cast<std::uint64_t>(static_cast<std::uint32_t>(key.x)) + (h << 6) + (h >> 2);
        h ^= static_cast<std::uint64_t>(static_cast<std::uint32_t>(key.y)) * 0xBF58476D1CE4E5B9ull +
             (h << 6) + (h >> 2);
        return static_cast<std::size_t>(h);
    }
};

}  // namespace sylva
