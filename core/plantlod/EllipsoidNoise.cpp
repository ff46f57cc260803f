#include "sylva/core/plantlod/EllipsoidNoise.h"

#include <bit>
#include <cmath>

namespace sylva {

namespace {

std::uint32_t pcg3d(std::uint32_t x, std::uint32_t y, std::uint32_t z) {
    x = x * 1664525u + 1013904223u;
    y = y * 1664525u + 1013904223u;
    z = z * 1664525u + 1013904223u;
    x += y * z;
    y += z * x;
    z += x * y;
    x ^= x >> 16u;
    y ^= y >> 16u;
    z ^= z >> 16u;
    x += y * z;
    y += z * x;
    z += x * y;
    return x ^ y ^ z;
}

}  // namespace

std::uint32_t ellipsoidNoiseSeed(const glm::vec3& center) {
    return std::bit_cast<std::uint32_t>(center.x) ^
           std::bit_cast<std::uint32_t>(center.y) * 0x9E3779B9u ^
           std::bit_cast<std::uint32_t>(center.z) * 0x85EBCA6Bu;
}

float ellipsoidNoise(const glm::vec3& q, float noiseLevel, std::uint32_t seed) {
    return ellipsoidNoiseCells(q, std::exp2(noiseLevel), seed);
}

float ellipsoidNoiseCells(const glm::vec3& q, float cells, std::uint32_t seed) {
    const auto cell = [&](float c) {
        return static_cast<std::uint32_t>(
            static_cast<std::int32_t>(std::floor((c * 0.5f + 0.5f) * cells)) + 4096);
    };
    const std::uint32_t value =
        pcg3d(cell(q.x) ^ seed, cell(q.y) ^ (seed * 0x27D4EB2Fu), cell(q.z) ^ (seed * 0x165667B1u));
    return static_cast<float>(value >> 8) * (1.0f / 16777216.0f);
}

}  // namespace sylva
