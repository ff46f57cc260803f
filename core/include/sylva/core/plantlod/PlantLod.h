// PlantLod: the output of the plant LoD builder (seed 001 ch. 3) in the form the
// vegetation renderer consumes (seed 001 §6.2, the generalized sequential primitive
// tree): two flat arrays, ellipsoids and lines, each ordered coarse → fine, where every
// primitive carries the error interval [errorMinimum, errorMaximum) in which it is drawn.
// For a tolerated error e the drawn set is a prefix of each array (all primitives with
// errorMaximum > e, because the arrays are sorted by errorMaximum descending) filtered by
// errorMinimum <= e, so a renderer draws a prefix and discards the rest in the vertex
// shader.
//
// Errors are metres per pixel (seed 001 §6.3): an ellipsoid level is drawn when its
// mean ellipsoid diameter covers about 5 pixels, a line when its width covers about one.
// The measured multi-scale RMSE of each level against the source mesh is kept separately
// (PlantLodLevel::imageError) for reports and tests.
//
// Frame: model space of the PlantModel (metres, +Z up). Colours: linear RGB.
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "sylva/core/plantlod/BillboardCloudBuilder.h"

namespace sylva {

// One ray-cast ellipsoid: centre + axes * radii (axes orthonormal, radii in metres,
// already multiplied by the calibrated primitive scale). Noise: the alpha test of
// ImageNoise.h with `noiseLevel` (mip level, 2^noiseLevel cells per unit-sphere diameter)
// and `alphaThreshold` (noise values below it are discarded; 0 = solid).
struct LodEllipsoid {
    glm::vec3 center{0.0f};
    glm::vec3 axes[3] = {{1.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, {0.0f, 0.0f, 1.0f}};
    glm::vec3 radii{0.0f};
    glm::vec3 color{0.0f};
    float weight = 0.0f;  // leaf area represented, m²
    float noiseLevel = 0.0f;
    float alphaThreshold = 0.0f;
    float ambientOcclusion = 1.0f;  // [0, 1], calibrated (seed 001 §6.5)
    float errorMinimum = 0.0f;      // metres per pixel
    float errorMaximum = std::numeric_limits<float>::infinity();
    std::uint32_t level = 0;  // 0 = imported leaves, coarser levels count up
};

// One line: a tapered capsule from start to end (radii in metres, calibrated scale
// applied).
struct LodLine {
    glm::vec3 start{0.0f};
    glm::vec3 end{0.0f};
    float startRadius = 0.0f;
    float endRadius = 0.0f;
    glm::vec3 color{0.0f};
    float weight = 0.0f;  // volume represented, m³ (seed 001 Fig. 3.12)
    float ambientOcclusion = 1.0f;
    float errorMinimum = 0.0f;
    float errorMaximum = std::numeric_limits<float>::infinity();
};

// One discrete level of the ellipsoid hierarchy, with the lines drawn at its error.
struct PlantLodLevel {
    float errorMinimum = 0.0f;  // metres per pixel; the level is drawn in [min, max)
    float errorMaximum = std::numeric_limits<float>::infinity();
    std::uint32_t ellipsoidCount = 0;
    std::uint32_t lineCount = 0;
    float imageError = 0.0f;      // multi-scale RMSE against the source mesh
    float alphaThreshold = 0.0f;  // calibrated noise alpha threshold of the level
    float primitiveScale = 1.0f;  // calibrated ellipsoid scale of the level
};

struct PlantLod {
    std::string name;
    glm::vec3 boundsMinimum{0.0f};
    glm::vec3 boundsMaximum{0.0f};
    std::vector<PlantLodLevel> levels;     // finest (imported leaves) first
    std::vector<LodEllipsoid> ellipsoids;  // coarse → fine (errorMaximum descending)
    std::vector<LodLine> lines;            // coarse → fine (errorMaximum descending)
    // Billboard clouds of the same model (seed 003), for comparison; empty when not
    // built. Levels read from a .plod have no trianglePlane map (it is not stored).
    BillboardCloud billboards;
};

}  // namespace sylva
