#include "sylva/core/sources/plants/PlantsSource.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <numbers>

#include "sylva/core/base/Hash.h"
#include "sylva/core/geo/Ellipsoid.h"
#include "sylva/core/sources/plants/InstanceTileCodec.h"
#include "sylva/core/sources/plants/PlantModelSource.h"
#include "sylva/core/sources/vector/CoverageRasterizer.h"

namespace sylva {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kTwoPi = 2.0 * std::numbers::pi;
// Candidate cells one call may visit: a few tenths of a second of work.
constexpr double kMaxCells = 8.0e6;
// The smallest meridional radius (at the equator): latitude margins in radians
// derived from it are at least as long in metres everywhere.
const double kEquatorMeridional =
    Ellipsoid::kSemiMajorAxis * (1.0 - Ellipsoid::kEccentricitySquared);

// SplitMix64 (Steele, Lea, Flood 2014): a tiny, well-mixed generator; one per cell.
class CellRandom {
public:
    explicit CellRandom(std::uint64_t seed) : state_(seed) {}
    double uniform() {  // [0, 1)
        std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        z ^= z >> 31;
        return static_cast<double>(z >> 11) * 0x1.0p-53;
    }

private:
    std::uint64_t state_;
};

// Murmur3's 64-bit finaliser: a bijective mix, so distinct cells get unrelated streams.
std::uint64_t mix(std::uint64_t x) {
    x ^= x >> 33;
    x *= 0xff51afd7ed558ccdull;
    x ^= x >> 33;
    x *= 0xc4ceb9fe1a85ec53ull;
    x ^= x >> 33;
    return x;
}

std::uint64_t cellSeed(std::uint64_t seed, std::int64_t a, std::int64_t b, std::uint64_t salt) {
    std::uint64_t h = mix(seed + 0x9E3779B97F4A7C15ull * (salt + 1));
    h = mix(h ^ static_cast<std::uint64_t>(a));
    return mix(h ^ (static_cast<std::uint64_t>(b) * 0xD6E8FEB86659FD93ull));
}

// Bilinear sample of channel 0 at a longitude/latitude inside the tile (or its border).
float sample(const ImageTile& tile, double longitude, double latitude) {
    const double fx = (longitude - tile.key().west()) / tile.texelWidth() - 0.5;
    const double fy = (tile.key().north() - latitude) / tile.texelHeight() - 0.5;
    const int lo = -tile.border(), hi = tile.size() + tile.border() - 2;
    const int ix = std::clamp(static_cast<int>(std::floor(fx)), lo, hi);
    const int iy = std::clamp(static_cast<int>(std::floor(fy)), lo, hi);
    const double tx = std::clamp(fx - ix, 0.0, 1.0), ty = std::clamp(fy - iy, 0.0, 1.0);
    const double top = tile.at(ix, iy, 0) * (1 - tx) + tile.at(ix + 1, iy, 0) * tx;
    const double bottom = tile.at(ix, iy + 1, 0) * (1 - tx) + tile.at(ix + 1, iy + 1, 0) * tx;
    return static_cast<float>(top * (1 - ty) + bottom * ty);
}

TileKey tileOf(const TileKey& like, double longitude, double latitude) {
    TileKey key = like;
    const double lon = std::remainder(longitude, kTwoPi);
    key.x = std::clamp(static_cast<int>(std::floor((lon + kPi) / kTwoPi * key.columns())), 0,
                       key.columns() - 1);
    key.y = std::clamp(static_cast<int>(std::floor((kPi / 2 - latitude) / kPi * key.rows())), 0,
                       key.rows() - 1);
    return key;
}

bool insidePolygon(const Feature& feature, double shift, double longitude, double latitude) {
    // Non-zero winding number of the oriented rings.
    int winding = 0;
    for (const std::vector<glm::dvec2>& ring : feature.parts) {
        for (std::size_t i = 0; i + 1 < ring.size(); ++i) {
            const glm::dvec2 a(ring[i].x + shift, ring[i].y),
                b(ring[i + 1].x + shift, ring[i + 1].y);
            const double side = (b.x - a.x) * (latitude - a.y) - (longitude - a.x) * (b.y - a.y);
            if (a.y <= latitude) {
                if (b.y > latitude && side > 0) {
                    ++winding;
                }
            } else if (b.y <= latitude && side < 0) {
                --winding;
            }
        }
    }
    return winding != 0;
}

std::string decimal(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.3g", value);
    return text;
}

std::optional<double> parseNumber(const std::string& text) {
    char* end = nullptr;
    const double value = std::strtod(text.c_str(), &end);
    if (end == text.c_str() || *end != '\0' || !std::isfinite(value)) {
        return std::nullopt;
    }
    return value;
}

}  // namespace

struct PlantsSource::Window {
    GeographicBounds bounds;       // unwrapped longitudes allowed
    std::optional<TileKey> owner;  // keep only instances owned by this tile
};

PlantsSource::PlantsSource(std::string name, const Source* elevation, const Source* density,
                           const FeatureSource* features, PlantsParameters parameters)
    : Source(std::move(name), "plants", PortType::Instances, 0),
      elevation_(elevation),
      density_(density),
      features_(features),
      parameters_(std::move(parameters)) {
    addInput(elevation_);
    if (density_ != nullptr) {
        addInput(density_);
    }
    if (features_ != nullptr) {
        addInput(features_);
    }
    ContentHash hash;
    hash.add(parameters_.perHectare).add(parameters_.spacing);
    for (const auto& [species, share] : parameters_.species) {
        hash.add(species).add(share);
    }
    hash.add(parameters_.speciesAttribute);
    for (const auto& [value, species] : parameters_.speciesMap) {
        hash.add(value).add(species);
    }
    hash.add(parameters_.scaleMinimum)
        .add(parameters_.scaleMaximum)
        .add(parameters_.scaleAttribute);
    hash.add(parameters_.rotationAttribute).add(parameters_.tintVariation).add(parameters_.seed);
    hash.add(density_ != nullptr).add(features_ != nullptr);
    setParameterHash(hash.value());

    double total = 0.0;
    for (const auto& [species, share] : parameters_.species) {
        speciesNames_.push_back(species);
        total += share;
    }
    double running = 0.0;
    for (const auto& [species, share] : parameters_.species) {
        running += share;
        speciesCumulative_.push_back(total > 0.0 ? running / total : 1.0);
    }
    for (const auto& [value, species] : parameters_.speciesMap) {
        if (std::find(speciesNames_.begin(), speciesNames_.end(), species) == speciesNames_.end()) {
            speciesNames_.push_back(species);
        }
    }
    cellSize_ = 0.99 * 100.0 / std::sqrt(parameters_.perHectare);
    rows_ = static_cast<int>(std::ceil(kPi * kEquatorMeridional / cellSize_));
    rowHeight_ = kPi / rows_;
    // The coarsest level whose texels (north-south, 256 per tile) are at most two cells:
    // fine enough to resolve the density at the spacing of the instances.
    sampleLevel_ = 0;
    while (sampleLevel_ < TileKey::kMaxLevel &&
           kPi * Ellipsoid::kMeanRadius / (256.0 * std::ldexp(1.0, sampleLevel_)) >
               2.0 * cellSize_) {
        ++sampleLevel_;
    }
}

Result<std::unique_ptr<PlantsSource>> PlantsSource::make(std::string name, const Source* elevation,
                                                         const Source* density,
                                                         const FeatureSource* features,
                                                         PlantsParameters parameters) {
    SYLVA_CHECK(elevation != nullptr && parameters.perHectare > 0.0);
    auto source = std::unique_ptr<PlantsSource>(
        new PlantsSource(std::move(name), elevation, density, features, std::move(parameters)));
    const double rowMetres = source->rowHeight_ * kEquatorMeridional;
    if (source->parameters_.spacing >= std::min(rowMetres, source->cellSize_)) {
        return Error{"spacing " + decimal(source->parameters_.spacing) +
                     " m must be less than the cell size " +
                     decimal(std::min(rowMetres, source->cellSize_)) + " m that per_hectare " +
                     decimal(source->parameters_.perHectare) + " gives"};
    }
    const bool scatters = density != nullptr || features != nullptr;
    if (scatters && source->parameters_.species.empty() &&
        (features == nullptr || source->parameters_.speciesAttribute.empty())) {
        return Error{"no species: give `species` (name = share) for scattering"};
    }
    return source;
}

const PlantsSource* PlantsSource::from(const Source* source) {
    if (source == nullptr || source->output() != PortType::Instances) {
        return nullptr;
    }
    return dynamic_cast<const PlantsSource*>(source);
}

Result<TilePointer> PlantsSource::produce(const TileKey& key, TileProvider& provider) const {
    Window window;
    window.bounds = {key.west(), key.south(), key.east(), key.north()};
    window.owner = key;
    Result<std::vector<PlantInstance>> made = generate(key, window, provider);
    if (!made) {
        return made.error();
    }
    return TilePointer(std::make_shared<ImageTile>(InstanceTileCodec::encode(key, made.value())));
}

int PlantsSource::minimumLevel() const {
    for (int level = 0; level <= TileKey::kMaxLevel; ++level) {
        const double side = kPi / std::ldexp(1.0, level) / rowHeight_;
        if (side * side <= kMaxCells / 2) {
            return level;
        }
    }
    return TileKey::kMaxLevel;
}

Result<std::vector<PlantInstance>> PlantsSource::generate(const TileKey& key, const Window& window,
                                                          TileProvider& provider) const {
    std::vector<PlantInstance> out;
    struct Inputs {
        TilePointer elevation, density;
    };
    std::map<TileKey, Inputs> tiles;
    auto inputsAt = [&](const TileKey& owner) -> Result<const Inputs*> {
        auto it = tiles.find(owner);
        if (it != tiles.end()) {
            return &it->second;
        }
        Inputs inputs;
        Result<TilePointer> elevation = provider.tile(*elevation_, owner);
        if (!elevation) {
            return elevation.error();
        }
        inputs.elevation = elevation.value();
        if (density_ != nullptr) {
            Result<TilePointer> density = provider.tile(*density_, owner);
            if (!density) {
                return density.error();
            }
            inputs.density = density.value();
        }
        return &tiles.emplace(owner, std::move(inputs)).first->second;
    };
    // Inputs are sampled at one fixed level, whatever level is asked for.
    TileKey sampleKey;
    sampleKey.level = sampleLevel_;
    auto keep = [&](double longitudeUnwrapped, double latitude) {
        if (window.owner) {
            // tileOf wraps the longitude, so ownership does not depend on the shift.
            return tileOf(key, longitudeUnwrapped, latitude) == *window.owner;
        }
        return longitudeUnwrapped >= window.bounds.west &&
               longitudeUnwrapped < window.bounds.east && latitude >= window.bounds.south &&
               latitude < window.bounds.north;
    };

    std::vector<FeatureHit> hits;
    if (features_ != nullptr) {
        Result<std::shared_ptr<const FeatureCollection>> collection = features_->collection();
        if (!collection) {
            return collection.error();
        }
        hits = collection.value()->query(window.bounds);
        const FeatureCollection& features = *collection.value();
        const std::optional<std::size_t> speciesField =
            parameters_.speciesAttribute.empty() ? std::nullopt
                                                 : features.field(parameters_.speciesAttribute);
        const std::optional<std::size_t> scaleField =
            parameters_.scaleAttribute.empty() ? std::nullopt
                                               : features.field(parameters_.scaleAttribute);
        const std::optional<std::size_t> rotationField =
            parameters_.rotationAttribute.empty() ? std::nullopt
                                                  : features.field(parameters_.rotationAttribute);
        const std::string where = features_->file().string() + ": ";
        for (const auto& [attribute, field] :
             {std::pair{&parameters_.speciesAttribute, speciesField},
              std::pair{&parameters_.scaleAttribute, scaleField},
              std::pair{&parameters_.rotationAttribute, rotationField}}) {
            if (!attribute->empty() && !field) {
                return Error{where + "no attribute '" + *attribute + "'"};
            }
        }
        for (const FeatureHit& hit : hits) {
            const Feature& feature = *hit.feature;
            if (feature.kind == GeometryKind::Line) {
                return Error{where + "feature " + std::to_string(feature.id) +
                             " is a line; plants takes points (instances) and polygons (areas to "
                             "scatter over)"};
            }
            if (feature.kind != GeometryKind::Point) {
                continue;
            }
            for (std::size_t index = 0; index < feature.parts.front().size(); ++index) {
                const glm::dvec2 p = feature.parts.front()[index];
                const double longitude = p.x + hit.longitudeShift;
                if (!keep(longitude, p.y)) {
                    continue;
                }
                CellRandom random(cellSeed(parameters_.seed, feature.id, std::int64_t(index), 2));
                PlantInstance instance;
                instance.longitude = p.x;
                instance.latitude = p.y;
                if (speciesField) {
                    const std::string& value = feature.attributes[*speciesField];
                    std::string species = value;
                    if (!parameters_.speciesMap.empty()) {
                        auto it = std::find_if(
                            parameters_.speciesMap.begin(), parameters_.speciesMap.end(),
                            [&](const auto& entry) { return entry.first == value; });
                        if (it == parameters_.speciesMap.end()) {
                            return Error{where + "feature " + std::to_string(feature.id) +
                                         ": species '" + value + "' (attribute '" +
                                         parameters_.speciesAttribute + "') is not in species_map"};
                        }
                        species = it->second;
                    }
                    auto found = std::find(speciesNames_.begin(), speciesNames_.end(), species);
                    if (found == speciesNames_.end()) {
                        return Error{where + "feature " + std::to_string(feature.id) +
                                     ": unknown species '" + species + "' (attribute '" +
                                     parameters_.speciesAttribute + "')"};
                    }
                    instance.species = static_cast<std::uint32_t>(found - speciesNames_.begin());
                    random.uniform();
                } else {
                    const double u = random.uniform();
                    instance.species = static_cast<std::uint32_t>(
                        std::lower_bound(speciesCumulative_.begin(), speciesCumulative_.end(), u) -
                        speciesCumulative_.begin());
                }
                const double uScale = random.uniform(), uRotation = random.uniform(),
                             uTint = random.uniform();
                instance.scale = static_cast<float>(
                    parameters_.scaleMinimum +
                    uScale * (parameters_.scaleMaximum - parameters_.scaleMinimum));
                if (scaleField) {
                    const std::optional<double> v = parseNumber(feature.attributes[*scaleField]);
                    if (!v) {
                        return Error{where + "feature " + std::to_string(feature.id) +
                                     ": attribute '" + parameters_.scaleAttribute +
                                     "' is not a number: '" + feature.attributes[*scaleField] +
                                     "'"};
                    }
                    instance.scale = static_cast<float>(*v);
                }
                instance.rotation = static_cast<float>(uRotation * kTwoPi);
                if (rotationField) {
                    const std::optional<double> v = parseNumber(feature.attributes[*rotationField]);
                    if (!v) {
                        return Error{where + "feature " + std::to_string(feature.id) +
                                     ": attribute '" + parameters_.rotationAttribute +
                                     "' is not a number: '" + feature.attributes[*rotationField] +
                                     "'"};
                    }
                    instance.rotation = static_cast<float>(*v * kPi / 180.0);
                }
                instance.tint = glm::vec3(
                    static_cast<float>(1.0 + (2.0 * uTint - 1.0) * parameters_.tintVariation));
                Result<const Inputs*> inputs = inputsAt(tileOf(sampleKey, longitude, p.y));
                if (!inputs) {
                    return inputs.error();
                }
                instance.height =
                    sample(*inputs.value()->elevation, instance.longitude, instance.latitude);
                out.push_back(instance);
            }
        }
    }

    // Scattering over the density mask and/or the polygons.
    std::vector<FeatureHit> polygons;
    for (const FeatureHit& hit : hits) {
        if (hit.feature->kind == GeometryKind::Polygon) {
            polygons.push_back(hit);
        }
    }
    if (density_ == nullptr && polygons.empty()) {
        return out;
    }
    if (speciesCumulative_.empty()) {
        return Error{"source '" + name() + "': scattering needs `species` (name = share)"};
    }
    const double half = 0.5 * parameters_.spacing;
    const double marginLatitude = half / kEquatorMeridional;
    const int rowFirst = std::clamp(
        static_cast<int>(std::floor((window.bounds.south + kPi / 2) / rowHeight_)), 0, rows_ - 1);
    const int rowLast = std::clamp(
        static_cast<int>(std::floor((window.bounds.north + kPi / 2) / rowHeight_)), 0, rows_ - 1);
    {
        const double equatorward =
            std::min(std::abs(window.bounds.south), std::abs(window.bounds.north));
        const double parallel =
            Ellipsoid::primeVerticalRadius(equatorward) *
            std::cos(window.bounds.south < 0 && window.bounds.north > 0 ? 0.0 : equatorward);
        const double cells =
            double(rowLast - rowFirst + 1) *
            ((window.bounds.east - window.bounds.west) * parallel / cellSize_ + 2.0);
        if (cells > kMaxCells) {
            return Error{"source '" + name() + "': tile " + key.toString() +
                         " is too coarse for plant instances (" +
                         std::to_string(static_cast<long long>(cells)) + " cells); request level " +
                         std::to_string(minimumLevel()) + " or finer"};
        }
    }
    const double densityScale = parameters_.perHectare / 1.0e4;
    for (int row = rowFirst; row <= rowLast; ++row) {
        const double south = -kPi / 2 + row * rowHeight_, north = south + rowHeight_;
        const double poleward = std::abs(south) > std::abs(north) ? south : north;
        if (std::abs(poleward) >= kPi / 2 - 1e-12) {
            continue;  // a cell touching the pole has no width to keep spacing in
        }
        const double parallel = Ellipsoid::primeVerticalRadius(poleward) * std::cos(poleward);
        const auto cellsInRow =
            static_cast<std::int64_t>(std::max(1.0, std::floor(kTwoPi * parallel / cellSize_)));
        const double cellWidth = kTwoPi / double(cellsInRow);
        const double marginLongitude = half / parallel;
        if (2.0 * marginLongitude >= cellWidth || 2.0 * marginLatitude >= rowHeight_) {
            continue;
        }
        const double cellArea = CoverageRasterizer::quadrangleArea(south, north, cellWidth);
        // Longitude intervals that may hold instances: the window, or the polygons' bounds in it.
        std::vector<std::pair<double, double>> intervals;
        if (density_ == nullptr) {
            for (const FeatureHit& hit : polygons) {
                const GeographicBounds& b = hit.feature->bounds;
                if (b.south > north || b.north < south) {
                    continue;
                }
                const double west = std::max(b.west + hit.longitudeShift, window.bounds.west);
                const double east = std::min(b.east + hit.longitudeShift, window.bounds.east);
                if (west <= east) {
                    intervals.emplace_back(west, east);
                }
            }
            std::sort(intervals.begin(), intervals.end());
        } else {
            intervals.emplace_back(window.bounds.west, window.bounds.east);
        }
        std::int64_t next = std::numeric_limits<std::int64_t>::min();
        for (const auto& [west, east] : intervals) {
            const auto first =
                std::max(next, static_cast<std::int64_t>(std::floor((west + kPi) / cellWidth)));
            const auto last = static_cast<std::int64_t>(std::floor((east + kPi) / cellWidth));
            for (std::int64_t cell = first; cell <= last; ++cell) {
                const std::int64_t wrapped = ((cell % cellsInRow) + cellsInRow) % cellsInRow;
                CellRandom random(cellSeed(parameters_.seed, row, wrapped, 1));
                const double latitude =
                    south + marginLatitude + random.uniform() * (rowHeight_ - 2 * marginLatitude);
                // The position comes from the wrapped cell, so the same instance has the
                // same bits whichever side of the antimeridian asks; the window test
                // uses it shifted by whole turns.
                const double longitude = -kPi + double(wrapped) * cellWidth + marginLongitude +
                                         random.uniform() * (cellWidth - 2 * marginLongitude);
                const double longitudeUnwrapped =
                    longitude + kTwoPi * double((cell - wrapped) / cellsInRow);
                const double accept = random.uniform();
                if (!keep(longitudeUnwrapped, latitude)) {
                    continue;
                }
                double density = 1.0;
                if (!polygons.empty()) {
                    density = 0.0;
                    for (const FeatureHit& hit : polygons) {
                        const GeographicBounds& b = hit.feature->bounds;
                        const double x = longitudeUnwrapped - hit.longitudeShift;
                        if (x >= b.west && x <= b.east && latitude >= b.south &&
                            latitude <= b.north && insidePolygon(*hit.feature, 0.0, x, latitude)) {
                            density = 1.0;
                            break;
                        }
                    }
                    if (density == 0.0) {
                        continue;
                    }
                }
                Result<const Inputs*> inputs = inputsAt(tileOf(sampleKey, longitude, latitude));
                if (!inputs) {
                    return inputs.error();
                }
                if (density_ != nullptr) {
                    density *= std::clamp(sample(*inputs.value()->density, longitude, latitude),
                                          0.0f, 1.0f);
                }
                if (accept >= density * densityScale * cellArea) {
                    continue;
                }
                PlantInstance instance;
                instance.longitude = longitude;
                instance.latitude = latitude;
                const double uSpecies = random.uniform();
                instance.species = static_cast<std::uint32_t>(
                    std::lower_bound(speciesCumulative_.begin(), speciesCumulative_.end(),
                                     uSpecies) -
                    speciesCumulative_.begin());
                instance.species = std::min<std::uint32_t>(
                    instance.species, std::uint32_t(speciesCumulative_.size() - 1));
                instance.scale = static_cast<float>(
                    parameters_.scaleMinimum +
                    random.uniform() * (parameters_.scaleMaximum - parameters_.scaleMinimum));
                instance.rotation = static_cast<float>(random.uniform() * kTwoPi);
                instance.tint = glm::vec3(static_cast<float>(1.0 + (2.0 * random.uniform() - 1.0) *
                                                                       parameters_.tintVariation));
                instance.height = sample(*inputs.value()->elevation, longitude, latitude);
                out.push_back(instance);
            }
            next = std::max(next, last + 1);
        }
    }
    return out;
}

Result<std::shared_ptr<const InstanceTile>> PlantsSource::instances(const TileKey& key,
                                                                    TileProvider& provider) const {
    // Through the provider: cached, shared and deduplicated like any tile.
    Result<TilePointer> encoded = provider.tile(*this, key);
    if (!encoded) {
        return encoded.error();
    }
    Result<std::vector<PlantInstance>> decoded = InstanceTileCodec::decode(*encoded.value());
    if (!decoded) {
        return decoded.error();
    }
    auto tile = std::make_shared<InstanceTile>();
    tile->key = key;
    tile->species = speciesNames_;
    tile->instances = std::move(decoded.value());
    return std::shared_ptr<const InstanceTile>(std::move(tile));
}

Result<std::vector<PlantInstance>> PlantsSource::instancesNear(const TileKey& key,
                                                               double marginMetres,
                                                               TileProvider& provider) const {
    Window window;
    const double poleward = std::max(std::abs(key.north()), std::abs(key.south()));
    const double marginLatitude = marginMetres / kEquatorMeridional;
    const double parallel =
        std::max(Ellipsoid::primeVerticalRadius(poleward) * std::cos(poleward), 1.0);
    const double marginLongitude = std::min(marginMetres / parallel, kPi);
    window.bounds = {key.west() - marginLongitude, std::max(key.south() - marginLatitude, -kPi / 2),
                     key.east() + marginLongitude, std::min(key.north() + marginLatitude, kPi / 2)};
    return generate(key, window, provider);
}

Result<std::unique_ptr<Source>> PlantsSource::create(const SourceBuildContext& context) {
    const BlockReader& reader = context.reader;
    Result<const Source*> elevation = context.input("elevation", true);
    if (!elevation) {
        return elevation.error();
    }
    if (elevation.value()->output() != PortType::Elevation) {
        return Error{reader.where("elevation") + "'elevation' must be an elevation, but source '" +
                     elevation.value()->name() + "' gives " +
                     portTypeName(elevation.value()->output())};
    }
    Result<const Source*> density = context.input("density", false);
    if (!density) {
        return density.error();
    }
    Result<const Source*> features = context.input("features", false);
    if (!features) {
        return features.error();
    }
    const FeatureSource* featureSource = FeatureSource::from(features.value());
    if (features.value() != nullptr && featureSource == nullptr) {
        return Error{reader.where("features") + "'features' must be a features source"};
    }
    PlantsParameters p;
    p.perHectare = reader.optionalNumber("per_hectare").value_or(100.0);
    p.spacing = reader.optionalNumber("spacing").value_or(0.0);
    if (const Value* species = reader.value("species")) {
        if (const ValueObject* object = species->get<ValueObject>()) {
            for (const auto& [key, value] : *object) {
                const Quantity* share = value.get<Quantity>();
                if (share == nullptr || share->value <= 0.0) {
                    return Error{reader.where("species") + "species '" + key +
                                 "' needs a positive share (e.g. 40%)"};
                }
                p.species.emplace_back(key, share->value);
            }
        }
    }
    p.speciesAttribute = reader.string("species_attribute");
    if (const Value* map = reader.value("species_map")) {
        if (const ValueObject* object = map->get<ValueObject>()) {
            for (const auto& [key, value] : *object) {
                const std::string* name = value.get<std::string>();
                const Word* word = value.get<Word>();
                if (name == nullptr && word == nullptr) {
                    return Error{reader.where("species_map") + "species_map '" + key +
                                 "' must name a species (a string)"};
                }
                p.speciesMap.emplace_back(key, name != nullptr ? *name : word->text);
            }
        }
    }
    if (const Value* scale = reader.value("scale")) {
        if (const ValueList* list = scale->get<ValueList>()) {
            if (list->size() != 2 || (*list)[0].get<Quantity>() == nullptr ||
                (*list)[1].get<Quantity>() == nullptr) {
                return Error{reader.where("scale") + "scale must be [minimum, maximum]"};
            }
            p.scaleMinimum = (*list)[0].get<Quantity>()->value;
            p.scaleMaximum = (*list)[1].get<Quantity>()->value;
        }
    }
    p.scaleAttribute = reader.string("scale_attribute");
    p.rotationAttribute = reader.string("rotation_attribute");
    p.tintVariation = reader.optionalNumber("tint_variation").value_or(0.1);
    p.seed = static_cast<std::uint64_t>(reader.optionalNumber("seed").value_or(1.0));
    Result<std::unique_ptr<PlantsSource>> made =
        make(context.block.name, elevation.value(), density.value(), featureSource, std::move(p));
    if (!made) {
        return Error{reader.where() + made.error().message};
    }
    // Models: species name = model source name; every species needs one.
    if (reader.value("models") != nullptr && context.inputList != nullptr) {
        Result<std::vector<const Source*>> models = (*context.inputList)("models");
        if (!models) {
            return models.error();
        }
        std::vector<const PlantModelSource*> byName;
        for (const Source* source : models.value()) {
            const PlantModelSource* model = PlantModelSource::from(source);
            if (model == nullptr) {
                return Error{reader.where("models") +
                             "'models' expects plant_model sources, but '" + source->name() +
                             "' gives " + portTypeName(source->output())};
            }
            byName.push_back(model);
        }
        PlantsSource& plants = *made.value();
        for (const std::string& species : plants.speciesNames_) {
            auto found = std::find_if(byName.begin(), byName.end(), [&](const PlantModelSource* m) {
                return m->name() == species;
            });
            if (found == byName.end()) {
                std::string known;
                for (const PlantModelSource* m : byName) {
                    known += (known.empty() ? "" : ", ") + m->name();
                }
                return Error{reader.where("models") + "species '" + species +
                             "' has no plant model: `models` lists " +
                             (known.empty() ? std::string("none") : known) +
                             " (a plant_model source named like the species draws it)"};
            }
            plants.models_.push_back(*found);
        }
        plants.modelSources_ = std::move(byName);
    } else {
        made.value()->models_.assign(made.value()->speciesNames_.size(), nullptr);
    }
    return std::unique_ptr<Source>(std::move(made.value()));
}

}  // namespace sylva
