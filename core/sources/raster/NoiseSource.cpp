#include "sylva/core/sources/raster/NoiseSource.h"

#include <algorithm>
#include <cmath>

#include "sylva/core/base/Hash.h"
#include "sylva/core/base/WorkerPool.h"
#include "sylva/core/geo/Ellipsoid.h"

namespace sylva {
namespace {

constexpr double kSelfSimilarBelow = 4000.0;  // metres

}  // namespace

NoiseSource::NoiseSource(std::string name, const NoiseParameters& parameters)
    : Source(std::move(name), "noise", PortType::Elevation, 1),
      parameters_(parameters),
      noise_(parameters.seed) {
    ContentHash hash;
    hash.add(parameters.seed)
        .add(parameters.amplitude)
        .add(parameters.baseWavelength)
        .add(parameters.octaves)
        .add(parameters.lacunarity)
        .add(parameters.gain)
        .add(parameters.ridges)
        .add(parameters.ridgeWavelength)
        .add(parameters.roughness)
        .add(parameters.offset);
    setParameterHash(hash.value());
}

namespace {

// Fade an octave out between 4 and 2 footprints per wavelength; 0 = skip.
double octaveWeight(double wavelength, double footprintMetres) {
    return footprintMetres > 0.0
               ? std::clamp(std::log2(wavelength / (2.0 * footprintMetres)), 0.0, 1.0)
               : 1.0;
}

// A fixed, irrational shift per octave decorrelates the lattices.
glm::dvec3 octaveShift(int octave, double phase) {
    return glm::dvec3(0.3183 * octave + 0.11 + phase, 0.5772 * octave + 0.37,
                      0.7071 * octave + 0.73 - phase);
}

}  // namespace

NoiseSource::OctaveWeights NoiseSource::octaveWeights(double footprintMetres) const {
    const NoiseParameters& p = parameters_;
    OctaveWeights weights;
    double wavelength = p.baseWavelength;
    for (int octave = 0; octave < p.octaves; ++octave) {
        const double weight = octaveWeight(wavelength, footprintMetres);
        if (weight <= 0.0)
            break;
        weights.continents.push_back(weight);
        wavelength /= p.lacunarity;
    }
    wavelength = p.ridgeWavelength;
    for (int octave = 0; p.ridges > 0.0 && octave < p.octaves; ++octave) {
        const double weight = octaveWeight(wavelength, footprintMetres);
        if (weight <= 0.0)
            break;
        weights.ridges.push_back(weight);
        wavelength /= p.lacunarity;
    }
    return weights;
}

double NoiseSource::height(const glm::dvec3& unitDirection, double footprintMetres) const {
    return height(unitDirection, octaveWeights(footprintMetres));
}

double NoiseSource::height(const glm::dvec3& unitDirection, const OctaveWeights& weights) const {
    const NoiseParameters& p = parameters_;
    double continents = 0.0;
    double amplitude = 1.0;
    double wavelength = p.baseWavelength;
    for (std::size_t octave = 0; octave < weights.continents.size(); ++octave) {
        continents += amplitude * weights.continents[octave] *
                      noise_(unitDirection * (Ellipsoid::kMeanRadius / wavelength) +
                             octaveShift(int(octave), 0.0));
        amplitude *= p.gain;
        wavelength /= p.lacunarity;
    }

    double mountains = 0.0;
    if (p.ridges > 0.0) {
        double previous = 1.0;
        amplitude = 1.0;
        wavelength = p.ridgeWavelength;
        for (std::size_t octave = 0; octave < weights.ridges.size(); ++octave) {
            const double n = noise_(unitDirection * (Ellipsoid::kMeanRadius / wavelength) +
                                    octaveShift(int(octave), 17.0));
            double signal = 1.0 - 2.0 * std::abs(n);  // crest where the noise crosses zero
            signal *= signal * previous;
            previous = std::clamp(0.4 + signal, 0.0, 1.0);
            mountains += amplitude * weights.ridges[octave] * signal;
            // Below a few kilometres real relief stops getting steeper with scale:
            // switch to ratio 1/2 (constant slope) so walker-scale terrain stays walkable.
            amplitude *= wavelength > kSelfSimilarBelow ? p.roughness : 0.5;
            wavelength /= p.lacunarity;
        }
        // Mountains rise on land only, growing with the distance from the coast.
        const double land = std::clamp((continents + 0.02) / 0.25, 0.0, 1.0);
        mountains *= land * land * (3.0 - 2.0 * land);
    }
    return p.amplitude * ((1.0 - p.ridges) * continents + p.ridges * mountains) + p.offset;
}

Result<TilePointer> NoiseSource::produce(const TileKey& key, TileProvider& provider) const {
    const TileFormat& format = provider.format();
    auto tile = std::make_shared<ImageTile>(key, format.size, format.border, 1);
    const int begin = -format.border;
    const int end = format.size + format.border;
    // Rows are independent: synthesise them in parallel (noise dominates tile cost).
    WorkerPool::shared().run(end - begin, [&](int rowIndex) {
        const int iy = begin + rowIndex;
        const double latitude = tile->texelLatitude(iy);
        const double cosLat = std::cos(latitude);
        const double sinLat = std::sin(latitude);
        // The footprint is the larger side of the texel on the ground.
        const double footprint =
            Ellipsoid::kMeanRadius *
            std::max(tile->texelHeight(), tile->texelWidth() * std::abs(cosLat));
        const OctaveWeights weights = octaveWeights(footprint);
        float* row = tile->row(iy);
        for (int ix = begin; ix < end; ++ix) {
            const double longitude = tile->texelLongitude(ix);
            const glm::dvec3 direction(cosLat * std::cos(longitude), cosLat * std::sin(longitude),
                                       sinLat);
            row[ix - begin] = static_cast<float>(height(direction, weights));
        }
    });
    return TilePointer(std::move(tile));
}

Result<std::unique_ptr<Source>> NoiseSource::create(const SourceBuildContext& context) {
    const Block& block = context.block;
    const BlockReader& reader = context.reader;
    NoiseParameters p;
    for (auto [name, target] : {std::pair{"amplitude", &p.amplitude},
                                {"base_wavelength", &p.baseWavelength},
                                {"lacunarity", &p.lacunarity},
                                {"gain", &p.gain},
                                {"ridges", &p.ridges},
                                {"ridge_wavelength", &p.ridgeWavelength},
                                {"roughness", &p.roughness},
                                {"offset", &p.offset}}) {
        Result<double> v = reader.number(name);
        if (!v) {
            return v.error();
        }
        *target = v.value();
    }
    Result<double> seed = reader.number("seed");
    Result<double> octaves = reader.number("octaves");
    if (!seed) {
        return seed.error();
    }
    if (!octaves) {
        return octaves.error();
    }
    p.seed = static_cast<std::uint32_t>(seed.value());
    p.octaves = static_cast<int>(octaves.value());
    return std::unique_ptr<Source>(std::make_unique<NoiseSource>(block.name, p));
}

}  // namespace sylva
