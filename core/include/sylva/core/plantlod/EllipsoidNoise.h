// EllipsoidNoise: the 3-D white noise that perforates ray-cast ellipsoids (seed 001
// §3.4.1, Fig. 3.9). The thesis uses a mip-mapped cube map of white noise; this is the
// same idea as a pure function, so the GPU shader can reproduce it bit for bit:
//
//   q     = hit point in the ellipsoid's unit-sphere frame, components in [-1, 1]
//   cells = exp2(noiseLevel)                       (cells per unit-sphere diameter)
//   cell  = ivec3(floor((q * 0.5 + 0.5) * cells))   (nearest texel, no filtering)
//   seed  = floatBitsToUint(center.x) ^ floatBitsToUint(center.y) * 0x9E3779B9u
//           ^ floatBitsToUint(center.z) * 0x85EBCA6Bu
//   value = hash(uvec3(cell + 4096) ^ uvec3(seed, seed * 0x27D4EB2Fu, seed * 0x165667B1u))
//   alpha = float(value >> 8u) / 16777216.0         ([0, 1), exact in float)
//   hash  = the PCG3D hash (Jarzynski & Olano 2020): v = v * 1664525u + 1013904223u;
//           v.x += v.y*v.z; v.y += v.z*v.x; v.z += v.x*v.y; v ^= v >> 16u;
//           v.x += v.y*v.z; v.y += v.z*v.x; v.z += v.x*v.y; return v.x ^ v.y ^ v.z
//
// A fragment is discarded when value < alphaThreshold. All arithmetic is 32-bit
// unsigned with wrap-around, identical in C++ and GLSL.
#pragma once

#include <cstdint>

#include <glm/glm.hpp>

namespace sylva {

std::uint32_t ellipsoidNoiseSeed(const glm::vec3& center);

// Noise value in [0, 1) at unit-sphere point `q` for the given mip level and seed.
float ellipsoidNoise(const glm::vec3& q, float noiseLevel, std::uint32_t seed);
// The same with cells = exp2(noiseLevel) computed once per ellipsoid.
float ellipsoidNoiseCells(const glm::vec3& q, float cells, std::uint32_t seed);

}  // namespace sylva
