// HypsometricSource (`source x : hypsometric`): an elevation-driven colour source.
// A ramp of (height, colour) stops coloured by elevation, water below 0 m (shallow
// to deep over water_depth), and rock on steep slopes. Colours are given in sRGB and
// interpolated in linear RGB; output is linear RGBA (alpha 1). Each texel is the mean
// colour of the heights it spans (the height change across it from central differences),
// so thin bands (beach, coast) keep their area at coarse levels instead of filling texels.
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "sylva/core/sources/Source.h"
#include "sylva/core/sources/SourceBuildContext.h"

namespace sylva {

struct HypsometricStop {
    double height = 0.0;  // metres
    glm::vec3 color{};    // linear RGB
};

struct HypsometricParameters {
    std::vector<HypsometricStop> ramp;  // ascending heights; empty: defaultRamp()
    glm::vec3 water{};                  // linear RGB
    glm::vec3 shallowWater{};           // linear RGB
    double waterDepth = 400.0;          // metres
    glm::vec3 rock{};                   // linear RGB
    double slopeStart = 0.49;           // radians
    double slopeEnd = 0.79;             // radians

    static std::vector<HypsometricStop> defaultRamp();
};

class HypsometricSource final : public Source {
public:
    // `normals` may be null: slopes then come from `height` directly.
    HypsometricSource(std::string name, const Source* height, const Source* normals,
                      HypsometricParameters parameters);

    // From a `source x : hypsometric` block.
    static Result<std::unique_ptr<Source>> create(const SourceBuildContext& context);

    Result<TilePointer> produce(const TileKey& key, TileProvider& provider) const override;

    // Linear RGB for a height (metres) and a slope angle (radians).
    glm::vec3 colorAt(double height, double slope) const;
    // The mean of colorAt over heights uniform in [low, high] (metres): a texel's colour
    // when its heights span that range (exact for the piecewise-linear land ramp).
    glm::vec3 meanColor(double low, double high, double slope) const;

private:
    const Source* height_;
    const Source* normals_;
    HypsometricParameters parameters_;
};

}  // namespace sylva
