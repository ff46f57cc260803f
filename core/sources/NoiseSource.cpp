#include "sylva/core/sources/NoiseSource.h"

#include <algorithm>
#include <cmath>

#include "sylva/core/base/Hash.h"
#include "sylva/core/geo/Ellipsoid.h"

namespace sylva {

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
        .add(parameters.offset);
    setParameterHash(hash.value());
}

double NoiseSource::height(const glm::dvec3& unitDirection, double footprintMetres) const {
    const NoiseParameters& p = parameters_;
    const glm::dvec3 base = unitDirection * (Ellipsoid::kMeanRadius / p.baseWavelength);
    double sum = 0.0;
    double amplitude = 1.0;
    double frequency = 1.0;
    for (int octave = 0; octave < p.octaves; ++octave) {
        const double wavelength = p.baseWavelength / frequency;
        double weight = 1.0;
        if (footprintMetres > 0.0) {
            // Fade the octave out between 4 and 2 footprints per wavelength.
            weight = std::clamp(std::log2(wavelength / (2.0 * footprintMetres)), 0.0, 1.0);
            if (weight <= 0.0) {
                break;
            }
        }
        // A fixed, irrational shift per octave decorrelates the lattices.
        const glm::dvec3 shift(0.3183 * octave + 0.11, 0.5772 * octave + 0.37, 0.7071 * octave + 0.73);
        const double n = noise_(base * frequency + shift);
        const double ridge = 1.0 - 2.0 * std::abs(n);  // crest where n crosses zero
        sum += amplitude * weight * ((1.0 - p.ridges) * n + p.ridges * ridge * 0.5);
        amplitude *= p.gain;
        frequency *= p.lacunarity;
    }
    return p.amplitude * sum + p.offset;
}

Result<TilePointer> NoiseSource::produce(const TileKey& key, TileProvider& provider) const {
    const TileFormat& format = provider.format();
    auto tile = std::make_shared<ImageTile>(key, format.size, format.border, 1);
    const int begin = -format.border;
    const int end = format.size + format.border;
    for (int iy = begin; iy < end; ++iy) {
        const double latitude = tile->texelLatitude(iy);
        const double cosLat = std::cos(latitude);
        const double sinLat = std::sin(latitude);
        // The footprint is the larger side of the texel on the ground.
        const double footprint =
            Ellipsoid::kMeanRadius * std::max(tile->texelHeight(), tile->texelWidth() * std::abs(cosLat));
        float* row = tile->row(iy);
        for (int ix = begin; ix < end; ++ix) {
            const double longitude = tile->texelLongitude(ix);
            const glm::dvec3 direction(cosLat * std::cos(longitude), cosLat * std::sin(longitude), sinLat);
            row[ix - begin] = static_cast<float>(height(direction, footprint));
        }
    }
    return TilePointer(std::move(tile));
}

}  // namespace sylva
