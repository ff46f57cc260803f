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

// Whether any polygon holds the point (1) or none (0).
double polygonDensity(const std::vector<FeatureHit>& polygons, double longitudeUnwrapped,
                      double latitude) {
    for (const FeatureHit& hit : polygons) {
        const GeographicBounds& b = hit.feature->bounds;
        const double x = longitudeUnwrapped - hit.longitudeShift;
        if (x >= b.west && x <= b.east && latitude >= b.south && latitude <= b.north &&
            insidePolygon(*hit.feature, 0.0, x, latitude)) {
            return 1.0;
        }
    }
    return 0.0;
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
    bool heights = true;           // false: instances' heights are 0 (no elevation read)

    // Whether an instance at this (unwrapped) position belongs to the window. `like`
    // gives the level of the owner tiles.
    bool keeps(const TileKey& like, double longitudeUnwrapped, double latitude) const {
        if (owner) {
            // tileOf wraps the longitude, so ownership does not depend on the shift.
            return tileOf(like, longitudeUnwrapped, latitude) == *owner;
        }
        return longitudeUnwrapped >= bounds.west && longitudeUnwrapped < bounds.east &&
               latitude >= bounds.south && latitude < bounds.north;
    }
};

// One row of the global grid: its cells and the margins that keep the spacing.
struct PlantsSource::RowCells {
    int row = 0;
    double south = 0.0;      // radians
    std::int64_t count = 1;  // cells around the parallel
    double width = 0.0;      // radians of longitude
    double marginLongitude = 0.0, marginLatitude = 0.0;
    double area = 0.0;  // m² of one cell
};

// The input tiles at the sample level (inputs are sampled at one fixed level, whatever
// level is asked for), each fetched once per generate().
class PlantsSource::InputTiles {
public:
    struct Inputs {
        TilePointer elevation, density;
    };

    // `elevation` nullptr: heights are not wanted (heightAt gives 0).
    InputTiles(const Source* elevation, const Source* density, int sampleLevel,
               TileProvider& provider)
        : elevation_(elevation), density_(density), provider_(provider) {
        sampleKey_.level = sampleLevel;
    }

    // The tiles holding a longitude/latitude (radians): the density tile; the elevation
    // tile only once heightAt asked for a position in it.
    Result<Inputs*> at(double longitude, double latitude) {
        const TileKey owner = tileOf(sampleKey_, longitude, latitude);
        auto it = tiles_.find(owner);
        if (it != tiles_.end()) {
            return &it->second;
        }
        Inputs inputs;
        if (density_ != nullptr) {
            Result<TilePointer> density = provider_.tile(*density_, owner);
            if (!density) {
                return density.error();
            }
            inputs.density = density.value();
        }
        return &tiles_.emplace(owner, std::move(inputs)).first->second;
    }

    // The terrain height (metres) at a kept instance. The elevation tile is fetched on the
    // first instance in it, not with the density: a sample tile without instances (no
    // forest there) never makes the provider produce the elevation chain (fractal noise,
    // blends: most of an instance tile's cost), and callers that draw instances in plan
    // want no heights at all (issue 20: a colour tile's markers held a worker for 30 s).
    Result<double> heightAt(double longitude, double latitude) {
        if (elevation_ == nullptr) {
            return 0.0;
        }
        Result<Inputs*> tiles = at(longitude, latitude);
        if (!tiles) {
            return tiles.error();
        }
        Inputs& inputs = *tiles.value();
        if (!inputs.elevation) {
            Result<TilePointer> elevation =
                provider_.tile(*elevation_, tileOf(sampleKey_, longitude, latitude));
            if (!elevation) {
                return elevation.error();
            }
            inputs.elevation = elevation.value();
        }
        return double(sample(*inputs.elevation, longitude, latitude));
    }

private:
    const Source* elevation_;
    const Source* density_;
    TileProvider& provider_;
    TileKey sampleKey_;
    std::map<TileKey, Inputs> tiles_;
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
    parameterHash_ = hash.value();
    setParameterHash(parameterHash_);

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
    source->setSeasons(PlantSeasons());
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
    InputTiles inputs(window.heights ? elevation_ : nullptr, density_, sampleLevel_, provider);
    std::vector<FeatureHit> polygons;
    if (features_ != nullptr) {
        Result<std::shared_ptr<const FeatureCollection>> collection = features_->collection();
        if (!collection) {
            return collection.error();
        }
        const std::vector<FeatureHit> hits = collection.value()->query(window.bounds);
        if (Status placed = placePoints(hits, *collection.value(), key, window, inputs, out);
            !placed) {
            return placed.error();
        }
        for (const FeatureHit& hit : hits) {
            if (hit.feature->kind == GeometryKind::Polygon) {
                polygons.push_back(hit);
            }
        }
    }
    if (density_ == nullptr && polygons.empty()) {
        if (Status dropped = dropExcluded(window, out); !dropped) {
            return dropped.error();
        }
        return out;
    }
    if (speciesCumulative_.empty()) {
        return Error{"source '" + name() + "': scattering needs `species` (name = share)"};
    }
    if (Status scattered = scatter(polygons, key, window, inputs, out); !scattered) {
        return scattered.error();
    }
    if (Status dropped = dropExcluded(window, out); !dropped) {
        return dropped.error();
    }
    return out;
}

void PlantsSource::excludeInside(const FeatureSource* footprints) {
    SYLVA_CHECK(footprints != nullptr && exclude_ == nullptr);
    exclude_ = footprints;
    addInput(exclude_);
    setParameterHash(ContentHash().add(parameterHash_).add(std::string_view("exclude")).value());
}

Status PlantsSource::dropExcluded(const Window& window, std::vector<PlantInstance>& out) const {
    if (exclude_ == nullptr || out.empty()) {
        return Status::success();
    }
    Result<std::shared_ptr<const FeatureCollection>> collection = exclude_->collection();
    if (!collection) {
        return collection.error();
    }
    std::vector<FeatureHit> polygons;
    for (const FeatureHit& hit : collection.value()->query(window.bounds)) {
        if (hit.feature->kind == GeometryKind::Polygon) {
            polygons.push_back(hit);
        }
    }
    if (!polygons.empty()) {
        std::erase_if(out, [&](const PlantInstance& instance) {
            return polygonDensity(polygons, instance.longitude, instance.latitude) > 0.0;
        });
    }
    return Status::success();
}

// ---------------------------------------------------------------------------- points

// The attributes of point features the parameters name (checked to exist).
struct PlantsSource::PointFields {
    std::optional<std::size_t> species, scale, rotation;
};

Result<PlantsSource::PointFields> PlantsSource::pointFields(
    const FeatureCollection& features) const {
    PointFields fields;
    const auto field = [&](const std::string& attribute) {
        return attribute.empty() ? std::nullopt : features.field(attribute);
    };
    fields.species = field(parameters_.speciesAttribute);
    fields.scale = field(parameters_.scaleAttribute);
    fields.rotation = field(parameters_.rotationAttribute);
    for (const auto& [attribute, found] :
         {std::pair{&parameters_.speciesAttribute, fields.species},
          std::pair{&parameters_.scaleAttribute, fields.scale},
          std::pair{&parameters_.rotationAttribute, fields.rotation}}) {
        if (!attribute->empty() && !found) {
            return Error{features_->file().string() + ": no attribute '" + *attribute + "'"};
        }
    }
    return fields;
}

Status PlantsSource::placePoints(const std::vector<FeatureHit>& hits,
                                 const FeatureCollection& features, const TileKey& key,
                                 const Window& window, InputTiles& inputs,
                                 std::vector<PlantInstance>& out) const {
    Result<PointFields> fields = pointFields(features);
    if (!fields) {
        return fields.error();
    }
    const std::string where = features_->file().string() + ": ";
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
            if (!window.keeps(key, longitude, p.y)) {
                continue;
            }
            Result<PlantInstance> instance = pointInstance(feature, index, *fields, where);
            if (!instance) {
                return instance.error();
            }
            Result<double> height = inputs.heightAt(instance->longitude, instance->latitude);
            if (!height) {
                return height.error();
            }
            instance->height = height.value();
            out.push_back(*instance);
        }
    }
    return Status::success();
}

// The species of a point: its attribute (through species_map) when one is named.
Result<std::uint32_t> PlantsSource::pointSpecies(const Feature& feature, std::size_t field,
                                                 const std::string& where) const {
    const std::string& value = feature.attributes[field];
    std::string species = value;
    if (!parameters_.speciesMap.empty()) {
        auto it = std::find_if(parameters_.speciesMap.begin(), parameters_.speciesMap.end(),
                               [&](const auto& entry) { return entry.first == value; });
        if (it == parameters_.speciesMap.end()) {
            return Error{where + "feature " + std::to_string(feature.id) + ": species '" + value +
                         "' (attribute '" + parameters_.speciesAttribute +
                         "') is not in species_map"};
        }
        species = it->second;
    }
    auto found = std::find(speciesNames_.begin(), speciesNames_.end(), species);
    if (found == speciesNames_.end()) {
        return Error{where + "feature " + std::to_string(feature.id) + ": unknown species '" +
                     species + "' (attribute '" + parameters_.speciesAttribute + "')"};
    }
    return static_cast<std::uint32_t>(found - speciesNames_.begin());
}

// A number attribute of a point, named `attribute` in messages.
Result<double> PlantsSource::pointNumber(const Feature& feature, std::size_t field,
                                         const std::string& attribute,
                                         const std::string& where) const {
    const std::optional<double> v = parseNumber(feature.attributes[field]);
    if (!v) {
        return Error{where + "feature " + std::to_string(feature.id) + ": attribute '" + attribute +
                     "' is not a number: '" + feature.attributes[field] + "'"};
    }
    return *v;
}

// Point `index` of a feature as an instance (without its height): attributes where
// named, otherwise the point's own random stream (seeded by feature and index).
Result<PlantInstance> PlantsSource::pointInstance(const Feature& feature, std::size_t index,
                                                  const PointFields& fields,
                                                  const std::string& where) const {
    const glm::dvec2 p = feature.parts.front()[index];
    CellRandom random(cellSeed(parameters_.seed, feature.id, std::int64_t(index), 2));
    PlantInstance instance;
    instance.longitude = p.x;
    instance.latitude = p.y;
    if (fields.species) {
        Result<std::uint32_t> species = pointSpecies(feature, *fields.species, where);
        if (!species) {
            return species.error();
        }
        instance.species = *species;
        random.uniform();
    } else {
        const double u = random.uniform();
        instance.species = static_cast<std::uint32_t>(
            std::lower_bound(speciesCumulative_.begin(), speciesCumulative_.end(), u) -
            speciesCumulative_.begin());
    }
    const double uScale = random.uniform(), uRotation = random.uniform(), uTint = random.uniform();
    instance.scale = static_cast<float>(
        parameters_.scaleMinimum + uScale * (parameters_.scaleMaximum - parameters_.scaleMinimum));
    if (fields.scale) {
        Result<double> v = pointNumber(feature, *fields.scale, parameters_.scaleAttribute, where);
        if (!v) {
            return v.error();
        }
        instance.scale = static_cast<float>(*v);
    }
    instance.rotation = static_cast<float>(uRotation * kTwoPi);
    if (fields.rotation) {
        Result<double> v =
            pointNumber(feature, *fields.rotation, parameters_.rotationAttribute, where);
        if (!v) {
            return v.error();
        }
        instance.rotation = static_cast<float>(*v * kPi / 180.0);
    }
    instance.tint =
        glm::vec3(static_cast<float>(1.0 + (2.0 * uTint - 1.0) * parameters_.tintVariation));
    return instance;
}

// ---------------------------------------------------------------------------- scattering

// Scattering over the density mask and/or the polygons: the rows of the global grid that
// meet the window, after a check that the window is fine enough.
Status PlantsSource::scatter(const std::vector<FeatureHit>& polygons, const TileKey& key,
                             const Window& window, InputTiles& inputs,
                             std::vector<PlantInstance>& out) const {
    const int rowFirst = std::clamp(
        static_cast<int>(std::floor((window.bounds.south + kPi / 2) / rowHeight_)), 0, rows_ - 1);
    const int rowLast = std::clamp(
        static_cast<int>(std::floor((window.bounds.north + kPi / 2) / rowHeight_)), 0, rows_ - 1);
    const double equatorward =
        std::min(std::abs(window.bounds.south), std::abs(window.bounds.north));
    const double parallel =
        Ellipsoid::primeVerticalRadius(equatorward) *
        std::cos(window.bounds.south < 0 && window.bounds.north > 0 ? 0.0 : equatorward);
    const double cells = double(rowLast - rowFirst + 1) *
                         ((window.bounds.east - window.bounds.west) * parallel / cellSize_ + 2.0);
    if (cells > kMaxCells) {
        return Error{"source '" + name() + "': tile " + key.toString() +
                     " is too coarse for plant instances (" +
                     std::to_string(static_cast<long long>(cells)) + " cells); request level " +
                     std::to_string(minimumLevel()) + " or finer"};
    }
    for (int row = rowFirst; row <= rowLast; ++row) {
        if (Status done = scatterRow(row, polygons, key, window, inputs, out); !done) {
            return done;
        }
    }
    return Status::success();
}

// Longitude intervals of a row that may hold instances: the window, or (without a
// density) the polygons' bounds in it, sorted.
std::vector<std::pair<double, double>> PlantsSource::rowIntervals(
    const std::vector<FeatureHit>& polygons, const Window& window, double south,
    double north) const {
    std::vector<std::pair<double, double>> intervals;
    if (density_ != nullptr) {
        intervals.emplace_back(window.bounds.west, window.bounds.east);
        return intervals;
    }
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
    return intervals;
}

Status PlantsSource::scatterRow(int row, const std::vector<FeatureHit>& polygons,
                                const TileKey& key, const Window& window, InputTiles& inputs,
                                std::vector<PlantInstance>& out) const {
    const double half = 0.5 * parameters_.spacing;
    const double marginLatitude = half / kEquatorMeridional;
    const double south = -kPi / 2 + row * rowHeight_, north = south + rowHeight_;
    const double poleward = std::abs(south) > std::abs(north) ? south : north;
    if (std::abs(poleward) >= kPi / 2 - 1e-12) {
        return Status::success();  // a cell touching the pole has no width to keep spacing in
    }
    const double parallel = Ellipsoid::primeVerticalRadius(poleward) * std::cos(poleward);
    RowCells cells;
    cells.row = row;
    cells.south = south;
    cells.count =
        static_cast<std::int64_t>(std::max(1.0, std::floor(kTwoPi * parallel / cellSize_)));
    cells.width = kTwoPi / double(cells.count);
    cells.marginLongitude = half / parallel;
    cells.marginLatitude = marginLatitude;
    if (2.0 * cells.marginLongitude >= cells.width || 2.0 * marginLatitude >= rowHeight_) {
        return Status::success();
    }
    cells.area = CoverageRasterizer::quadrangleArea(south, north, cells.width);
    std::int64_t next = std::numeric_limits<std::int64_t>::min();
    for (const auto& [west, east] : rowIntervals(polygons, window, south, north)) {
        const auto first =
            std::max(next, static_cast<std::int64_t>(std::floor((west + kPi) / cells.width)));
        const auto last = static_cast<std::int64_t>(std::floor((east + kPi) / cells.width));
        for (std::int64_t cell = first; cell <= last; ++cell) {
            if (Status done = scatterCell(cells, cell, polygons, key, window, inputs, out); !done) {
                return done;
            }
        }
        next = std::max(next, last + 1);
    }
    return Status::success();
}

// The candidate of one cell (`cell` unwrapped: it may lie a whole turn off), kept with
// probability density × per_hectare × cell area.
Status PlantsSource::scatterCell(const RowCells& cells, std::int64_t cell,
                                 const std::vector<FeatureHit>& polygons, const TileKey& key,
                                 const Window& window, InputTiles& inputs,
                                 std::vector<PlantInstance>& out) const {
    const std::int64_t wrapped = ((cell % cells.count) + cells.count) % cells.count;
    CellRandom random(cellSeed(parameters_.seed, cells.row, wrapped, 1));
    const double latitude = cells.south + cells.marginLatitude +
                            random.uniform() * (rowHeight_ - 2 * cells.marginLatitude);
    // The position comes from the wrapped cell, so the same instance has the same bits
    // whichever side of the antimeridian asks; the window test uses it shifted by whole
    // turns.
    const double longitude = -kPi + double(wrapped) * cells.width + cells.marginLongitude +
                             random.uniform() * (cells.width - 2 * cells.marginLongitude);
    const double longitudeUnwrapped = longitude + kTwoPi * double((cell - wrapped) / cells.count);
    const double accept = random.uniform();
    if (!window.keeps(key, longitudeUnwrapped, latitude)) {
        return Status::success();
    }
    double density = 1.0;
    if (!polygons.empty()) {
        density = polygonDensity(polygons, longitudeUnwrapped, latitude);
        if (density == 0.0) {
            return Status::success();
        }
    }
    if (density_ != nullptr) {
        Result<InputTiles::Inputs*> tiles = inputs.at(longitude, latitude);
        if (!tiles) {
            return tiles.error();
        }
        density *= std::clamp(sample(*tiles.value()->density, longitude, latitude), 0.0f, 1.0f);
    }
    const double densityScale = parameters_.perHectare / 1.0e4;
    if (accept >= density * densityScale * cells.area) {
        return Status::success();
    }
    PlantInstance instance;
    instance.longitude = longitude;
    instance.latitude = latitude;
    const double uSpecies = random.uniform();
    instance.species = static_cast<std::uint32_t>(
        std::lower_bound(speciesCumulative_.begin(), speciesCumulative_.end(), uSpecies) -
        speciesCumulative_.begin());
    instance.species =
        std::min<std::uint32_t>(instance.species, std::uint32_t(speciesCumulative_.size() - 1));
    instance.scale = static_cast<float>(parameters_.scaleMinimum +
                                        random.uniform() *
                                            (parameters_.scaleMaximum - parameters_.scaleMinimum));
    instance.rotation = static_cast<float>(random.uniform() * kTwoPi);
    instance.tint = glm::vec3(
        static_cast<float>(1.0 + (2.0 * random.uniform() - 1.0) * parameters_.tintVariation));
    Result<double> height = inputs.heightAt(longitude, latitude);
    if (!height) {
        return height.error();
    }
    instance.height = height.value();
    out.push_back(instance);
    return Status::success();
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
    window.heights = false;  // drawn in plan (see the header)
    return generate(key, window, provider);
}

namespace {

// The block's attributes (defaults as the schema gives them).
Result<PlantsParameters> readParameters(const BlockReader& reader) {
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
    return p;
}

}  // namespace

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
    Result<PlantsParameters> p = readParameters(reader);
    if (!p) {
        return p.error();
    }
    Result<std::unique_ptr<PlantsSource>> made =
        make(context.block.name, elevation.value(), density.value(), featureSource, std::move(*p));
    if (!made) {
        return Error{reader.where() + made.error().message};
    }
    if (Status attached = made.value()->attachModels(context); !attached) {
        return attached.error();
    }
    SourceLocation problem;
    Result<PlantSeasons> seasons =
        PlantSeasons::read(context.block, made.value()->speciesNames(), &problem);
    if (!seasons) {
        return Error{problem.toString() + ": source '" + context.block.name +
                     "': " + seasons.error().message};
    }
    made.value()->setSeasons(std::move(seasons.value()));
    Result<const Source*> exclude = context.input("exclude", false);
    if (!exclude) {
        return exclude.error();
    }
    if (exclude.value() != nullptr) {
        const FeatureSource* footprints = FeatureSource::from(exclude.value());
        if (footprints == nullptr) {
            return Error{reader.where("exclude") + "'exclude' must be a features source"};
        }
        made.value()->excludeInside(footprints);
    }
    return std::unique_ptr<Source>(std::move(made.value()));
}

void PlantsSource::setSeasons(PlantSeasons seasons) {
    seasons_ = std::move(seasons);
    phenology_.clear();
    for (std::size_t i = 0; i < speciesNames_.size(); ++i) {
        const LeafHabit habit = i < models_.size() && models_[i] != nullptr
                                    ? models_[i]->leafHabit()
                                    : LeafHabit::Evergreen;
        phenology_.push_back(seasons_.phenologyOf(speciesNames_[i], habit));
    }
}

// Models: species name = model source name; every species needs one.
Status PlantsSource::attachModels(const SourceBuildContext& context) {
    const BlockReader& reader = context.reader;
    if (reader.value("models") == nullptr || context.inputList == nullptr) {
        models_.assign(speciesNames_.size(), nullptr);
        return Status::success();
    }
    Result<std::vector<const Source*>> models = (*context.inputList)("models");
    if (!models) {
        return models.error();
    }
    std::vector<const PlantModelSource*> byName;
    for (const Source* source : models.value()) {
        const PlantModelSource* model = PlantModelSource::from(source);
        if (model == nullptr) {
            return Error{reader.where("models") + "'models' expects plant_model sources, but '" +
                         source->name() + "' gives " + portTypeName(source->output())};
        }
        byName.push_back(model);
    }
    for (const std::string& species : speciesNames_) {
        auto found = std::find_if(byName.begin(), byName.end(),
                                  [&](const PlantModelSource* m) { return m->name() == species; });
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
        models_.push_back(*found);
    }
    modelSources_ = std::move(byName);
    return Status::success();
}

}  // namespace sylva
