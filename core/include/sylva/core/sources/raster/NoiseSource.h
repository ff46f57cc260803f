// NoiseSource (`source x : noise`): global fractal relief for synthetic planets.
// fBm of GradientNoise evaluated at the unit-sphere direction of each texel (so the
// surface is seamless across the antimeridian and at the poles), mixed with a ridged
// variant for mountain crests. Band-limited: octaves whose wavelength is below two
// texel footprints are faded out (one octave of fade), so every pyramid level is a
// filtered version of the same surface (cf. seed 001 §5.4.3 on clipmap filtering).
// Output: elevation in metres above the ellipsoid.
#pragma once

#include <glm/glm.hpp>

#include "sylva/core/sources/Source.h"
#include "sylva/core/sources/SourceBuildContext.h"
#include "sylva/core/sources/raster/GradientNoise.h"

namespace sylva {

struct NoiseParameters {
    std::uint32_t seed = 1;
    double amplitude = 2500.0;      // metres
    double baseWavelength = 4.0e6;  // metres
    int octaves = 24;
    double lacunarity = 2.0;
    double gain = 0.5;
    double ridges = 0.5;             // 0..1
    double ridgeWavelength = 2.0e5;  // metres
    double roughness = 0.6;          // amplitude ratio of ridged octaves
    double offset = 0.0;             // metres
};

class NoiseSource final : public Source {
public:
    NoiseSource(std::string name, const NoiseParameters& parameters);

    // From a `source x : noise` block.
    static Result<std::unique_ptr<Source>> create(const SourceBuildContext& context);

    Result<TilePointer> produce(const TileKey& key, TileProvider& provider) const override;

    // Height in metres at a unit direction (ECEF axes), with octaves limited to a
    // sampling footprint in metres (texel size); footprint 0 means all octaves.
    double height(const glm::dvec3& unitDirection, double footprintMetres) const;

    const NoiseParameters& parameters() const { return parameters_; }

    // The per-octave fade weights of one footprint (they depend on the footprint only, so
    // a tile row computes them once for all its texels): continents' octaves, then the
    // ridged ones; a list ends at the first octave faded out completely.
    struct OctaveWeights {
        std::vector<double> continents, ridges;
    };
    OctaveWeights octaveWeights(double footprintMetres) const;
    // height(unitDirection, footprint) with the weights of that footprint, bit for bit.
    double height(const glm::dvec3& unitDirection, const OctaveWeights& weights) const;

private:
    NoiseParameters parameters_;
    GradientNoise noise_;
};

}  // namespace sylva
