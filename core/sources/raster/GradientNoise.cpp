#include "sylva/core/sources/raster/GradientNoise.h"

#include <cmath>

namespace sylva {
namespace {

inline std::uint32_t hashLattice(std::int64_t x, std::int64_t y, std::int64_t z,
                                 std::uint32_t seed) {
    // A 64-bit mix (splitmix64 finaliser) of the three coordinates and the seed.
    std::uint64_t h = static_cast<std::uint64_t>(x) * 0x9E3779B97F4A7C15ull;
    h ^= static_cast<std::uint64_t>(y) * 0xC2B2AE3D27D4EB4Full;
    h ^= static_cast<std::uint64_t>(z) * 0x165667B19E3779F9ull;
    h ^= static_cast<std::uint64_t>(seed) * 0xD6E8FEB86659FD93ull;
    h ^= h >> 30;
    h *= 0xBF58476D1CE4E5B9ull;
    h ^= h >> 27;
    h *= 0x94D049BB133111EBull;
    h ^= h >> 31;
    return static_cast<std::uint32_t>(h);
}

inline double gradient(std::uint32_t hash, double x, double y, double z) {
    // Perlin's 12 cube-edge directions (16 entries, four repeated).
    switch (hash & 15u) {
        case 0:
            return x + y;
        case 1:
            return -x + y;
        case 2:
            return x - y;
        case 3:
            return -x - y;
        case 4:
            return x + z;
        case 5:
            return -x + z;
        case 6:
            return x - z;
        case 7:
            return -x - z;
        case 8:
            return y + z;
        case 9:
            return -y + z;
        case 10:
            return y - z;
        case 11:
            return -y - z;
        case 12:
            return x + y;
        case 13:
            return -y + z;
        case 14:
            return -x + y;
        default:
            return -y - z;
    }
}

inline double fade(double t) {
    return t * t * t * (t * (t * 6.0 - 15.0) + 10.0);
}
inline double lerp(double a, double b, double t) {
    return a + t * (b - a);
}

}  // namespace

double GradientNoise::operator()(const glm::dvec3& position) const {
    const double fx = std::floor(position.x);
    const double fy = std::floor(position.y);
    const double fz = std::floor(position.z);
    const auto ix = static_cast<std::int64_t>(fx);
    const auto iy = static_cast<std::int64_t>(fy);
    const auto iz = static_cast<std::int64_t>(fz);
    const double x = position.x - fx;
    const double y = position.y - fy;
    const double z = position.z - fz;
    const double u = fade(x), v = fade(y), w = fade(z);

    const double n000 = gradient(hashLattice(ix, iy, iz, seed_), x, y, z);
    const double n100 = gradient(hashLattice(ix + 1, iy, iz, seed_), x - 1, y, z);
    const double n010 = gradient(hashLattice(ix, iy + 1, iz, seed_), x, y - 1, z);
    const double n110 = gradient(hashLattice(ix + 1, iy + 1, iz, seed_), x - 1, y - 1, z);
    const double n001 = gradient(hashLattice(ix, iy, iz + 1, seed_), x, y, z - 1);
    const double n101 = gradient(hashLattice(ix + 1, iy, iz + 1, seed_), x - 1, y, z - 1);
    const double n011 = gradient(hashLattice(ix, iy + 1, iz + 1, seed_), x, y - 1, z - 1);
    const double n111 = gradient(hashLattice(ix + 1, iy + 1, iz + 1, seed_), x - 1, y - 1, z - 1);

    return lerp(lerp(lerp(n000, n100, u), lerp(n010, n110, u), v),
                lerp(lerp(n001, n101, u), lerp(n011, n111, u), v), w);
}

}  // namespace sylva
