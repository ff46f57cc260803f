// GradientNoise: 3D gradient noise (Perlin's improved noise, 2002: quintic fade,
// 12 cube-edge gradients) with the permutation table replaced by an integer hash of
// the lattice coordinates and the seed. The hash makes the noise non-periodic, which
// matters here because one planet-wide fBm spans 2^24 lattice cells in its finest
// octave. Output is roughly in [-1, 1], zero at lattice points, C2 continuous.
#pragma once

#include <cstdint>

#include <glm/glm.hpp>

namespace sylva {

class GradientNoise {
public:
    explicit GradientNoise(std::uint32_t seed) : seed_(seed) {}
    double operator()(const glm::dvec3& position) const;

private:
    std::uint32_t seed_;
};

}  // namespace sylva
