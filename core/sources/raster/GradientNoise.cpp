#include "sylva/core/sources/raster/GradientNoise.h"

#include <cmath>

namespace sylva {
namespace {

// The lattice hash: a 64-bit mix (splitmix64 finaliser) of the three coordinates and the
// seed, each first multiplied by its own odd constant. The products depend on one
// coordinate each, so a cell's eight corners share six of them (see operator()).
constexpr std::uint64_t kHashX = 0x9E3779B97F4A7C15ull;
constexpr std::uint64_t kHashY = 0xC2B2AE3D27D4EB4Full;
constexpr std::uint64_t kHashZ = 0x165667B19E3779F9ull;
constexpr std::uint64_t kHashSeed = 0xD6E8FEB86659FD93ull;

inline std::uint32_t finishHash(std::uint64_t h) {
    h ^= h >> 30;
    h *= 0xBF58476D1CE4E5B9ull;
    h ^= h >> 27;
    h *= 0x94D049BB133111EBull;
    h ^= h >> 31;
    return static_cast<std::uint32_t>(h);
}

// Perlin's 12 cube-edge directions (16 entries, four repeated: x+y, -y+z, -x+y, -y-z),
// as coefficients: a table lookup instead of a switch, whose random branch the hash
// makes unpredictable (it dominated the cost). The sums keep the switch's order of
// operations — (gx·x + gy·y) + gz·z with terms of 0 adding an exact zero — so the value
// is the switch's exactly (up to the sign of a zero result).
struct Gradient {
    double x, y, z;
};
constexpr Gradient kGradients[16] = {
    {1, 1, 0}, {-1, 1, 0}, {1, -1, 0}, {-1, -1, 0}, {1, 0, 1}, {-1, 0, 1}, {1, 0, -1}, {-1, 0, -1},
    {0, 1, 1}, {0, -1, 1}, {0, 1, -1}, {0, -1, -1}, {1, 1, 0}, {0, -1, 1}, {-1, 1, 0}, {0, -1, -1}};

inline double gradient(std::uint32_t hash, double x, double y, double z) {
    const Gradient& g = kGradients[hash & 15u];
    return g.x * x + g.y * y + g.z * z;
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

    const std::uint64_t hx0 = static_cast<std::uint64_t>(ix) * kHashX;
    const std::uint64_t hx1 = static_cast<std::uint64_t>(ix + 1) * kHashX;
    const std::uint64_t hy0 = static_cast<std::uint64_t>(iy) * kHashY;
    const std::uint64_t hy1 = static_cast<std::uint64_t>(iy + 1) * kHashY;
    const std::uint64_t hs = static_cast<std::uint64_t>(seed_) * kHashSeed;
    const std::uint64_t hz0 = static_cast<std::uint64_t>(iz) * kHashZ ^ hs;
    const std::uint64_t hz1 = static_cast<std::uint64_t>(iz + 1) * kHashZ ^ hs;

    const double n000 = gradient(finishHash(hx0 ^ hy0 ^ hz0), x, y, z);
    const double n100 = gradient(finishHash(hx1 ^ hy0 ^ hz0), x - 1, y, z);
    const double n010 = gradient(finishHash(hx0 ^ hy1 ^ hz0), x, y - 1, z);
    const double n110 = gradient(finishHash(hx1 ^ hy1 ^ hz0), x - 1, y - 1, z);
    const double n001 = gradient(finishHash(hx0 ^ hy0 ^ hz1), x, y, z - 1);
    const double n101 = gradient(finishHash(hx1 ^ hy0 ^ hz1), x - 1, y, z - 1);
    const double n011 = gradient(finishHash(hx0 ^ hy1 ^ hz1), x, y - 1, z - 1);
    const double n111 = gradient(finishHash(hx1 ^ hy1 ^ hz1), x - 1, y - 1, z - 1);

    return lerp(lerp(lerp(n000, n100, u), lerp(n010, n110, u), v),
                lerp(lerp(n001, n101, u), lerp(n011, n111, u), v), w);
}

}  // namespace sylva
