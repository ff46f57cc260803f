#include "sylva/core/sources/objects/BuildingsSource.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "BuildingExtruder.h"
#include "FeatureValues.h"
#include "sylva/core/base/Hash.h"
#include "sylva/core/geo/Ellipsoid.h"
#include "sylva/core/sources/GroundSampler.h"

namespace sylva {

namespace {

constexpr double kDegree = std::numbers::pi / 180.0;
// Walls reach this far below the lowest ground sample, so a dip of the terrain between
// samples never shows a gap under a wall.
constexpr double kWallSkirt = 0.5;

// One building: an outer ring (index into the feature's parts) with its holes.
struct Building {
    std::uint32_t feature = 0;
    std::vector<std::uint32_t> rings;  // parts of the feature: outer first
    glm::dvec2 reference{0.0};         // longitude/latitude of the outer ring's mean
    double height = 0.0;               // eaves above the base, metres
    RoofKind roof = RoofKind::Flat;
    double pitch = 0.0;
    std::uint32_t wallColor = 0, roofColor = 0;
};

std::optional<RoofKind> roofNamed(const std::string& name) {
    if (name == "flat")
        return RoofKind::Flat;
    if (name == "gable")
        return RoofKind::Gable;
    if (name == "hip")
        return RoofKind::Hip;
    if (name == "pyramid")
        return RoofKind::Pyramid;
    return std::nullopt;
}

double signedArea(const std::vector<glm::dvec2>& ring) {
    double area = 0.0;
    for (std::size_t i = 0; i + 1 < ring.size(); ++i) {
        area += ring[i].x * ring[i + 1].y - ring[i + 1].x * ring[i].y;
    }
    return 0.5 * area;
}

// The rings of a building in its local plane, open (the closing vertex dropped).
std::vector<Ring> localRings(const Feature& feature, const Building& building,
                             const LocalPlane& plane) {
    std::vector<Ring> rings;
    for (std::uint32_t index : building.rings) {
        const std::vector<glm::dvec2>& part = feature.parts[index];
        Ring ring;
        for (std::size_t i = 0; i + 1 < part.size(); ++i) {
            ring.push_back(plane.toLocal(part[i]));
        }
        rings.push_back(std::move(ring));
    }
    return rings;
}

}  // namespace

struct BuildingsSource::Prepared {
    std::shared_ptr<const FeatureCollection> collection;
    std::vector<Building> buildings;
    std::map<TileKey, std::vector<std::uint32_t>> byTile;
    GeographicBounds bounds = GeographicBounds::empty();
};

BuildingsSource::BuildingsSource(std::string name, const FeatureSource* features,
                                 const Source* elevation, BuildingsParameters parameters)
    : MeshSource(std::move(name), "buildings"),
      features_(features),
      elevation_(elevation),
      parameters_(std::move(parameters)) {
    addInput(features_);
    addInput(elevation_);
    const BuildingsParameters& p = parameters_;
    ContentHash hash;
    hash.add(p.height).add(p.heightAttribute).add(p.floorsAttribute).add(p.storeyHeight);
    hash.add(p.meanBase).add(p.roof).add(p.roofAttribute).add(p.pitch).add(p.pitchAttribute);
    for (const glm::vec3& c : {p.wallColor, p.roofColor}) {
        hash.add(c.r).add(c.g).add(c.b);
    }
    hash.add(p.wallColorAttribute).add(p.roofColorAttribute);
    setParameterHash(hash.value());
}

BuildingsSource::~BuildingsSource() = default;

namespace {

// Reads and checks the per-building values of one feature (height, roof, pitch, colours).
class BuildingReader {
public:
    BuildingReader(const FeatureCollection& collection, const FeatureSource& features,
                   const BuildingsParameters& parameters)
        : values_(collection, features.file().string()), parameters_(parameters) {}

    Status resolveFields() {
        for (auto [attribute, slot] : {std::pair{&parameters_.heightAttribute, &height_},
                                       std::pair{&parameters_.floorsAttribute, &floors_},
                                       std::pair{&parameters_.roofAttribute, &roof_},
                                       std::pair{&parameters_.pitchAttribute, &pitch_},
                                       std::pair{&parameters_.wallColorAttribute, &wallColor_},
                                       std::pair{&parameters_.roofColorAttribute, &roofColor_}}) {
            Result<std::optional<std::size_t>> field = values_.field(*attribute);
            if (!field) {
                return field.error();
            }
            *slot = field.value();
        }
        return Status::success();
    }

    Status read(const Feature& feature, Building& building) const {
        const std::string where = values_.where(feature);
        if (feature.kind != GeometryKind::Polygon) {
            return Error{where + "a building footprint must be a polygon, not a " +
                         (feature.kind == GeometryKind::Point ? "point" : "line")};
        }
        building.height = parameters_.height;
        if (height_ || floors_) {
            Result<double> value = values_.number(feature, height_ ? *height_ : *floors_);
            if (!value) {
                return value.error();
            }
            building.height = height_ ? value.value() : value.value() * parameters_.storeyHeight;
        }
        if (!(building.height > 0.0)) {
            return Error{where + "the building height must be positive, not " +
                         std::to_string(building.height) + " m"};
        }
        std::string roofName = parameters_.roof;
        if (roof_) {
            Result<std::string> value = values_.text(feature, *roof_);
            if (!value) {
                return value.error();
            }
            roofName = value.value();
        }
        const std::optional<RoofKind> roof = roofNamed(roofName);
        if (!roof) {
            return Error{where + "unknown roof '" + roofName + "' (flat, gable, hip, pyramid)"};
        }
        building.roof = *roof;
        building.pitch = parameters_.pitch;
        if (pitch_) {
            Result<double> value = values_.number(feature, *pitch_);
            if (!value) {
                return value.error();
            }
            if (value.value() < 0.0 || value.value() > 75.0) {
                return Error{where + "roof pitch " + std::to_string(value.value()) +
                             " is outside 0..75 degrees"};
            }
            building.pitch = value.value() * kDegree;
        }
        return readColors(feature, building);
    }

private:
    Status readColors(const Feature& feature, Building& building) const {
        const glm::vec3 wall = parameters_.wallColor, roof = parameters_.roofColor;
        building.wallColor = FeatureValues::packColor(wall.r, wall.g, wall.b);
        building.roofColor = FeatureValues::packColor(roof.r, roof.g, roof.b);
        for (auto [field, slot] : {std::pair{wallColor_, &building.wallColor},
                                   std::pair{roofColor_, &building.roofColor}}) {
            if (!field) {
                continue;
            }
            Result<std::string> value = values_.text(feature, *field);
            if (!value) {
                return value.error();
            }
            const std::optional<std::uint32_t> color = FeatureValues::parseHexColor(value.value());
            if (!color) {
                return Error{values_.where(feature) + "'" + value.value() +
                             "' is not a colour (#rrggbb)"};
            }
            *slot = *color;
        }
        return Status::success();
    }

    FeatureValues values_;
    const BuildingsParameters& parameters_;
    std::optional<std::size_t> height_, floors_, roof_, pitch_, wallColor_, roofColor_;
};

// Splits a polygon feature into buildings (one per outer ring) and checks each
// footprint's validity with GEOS.
Status splitFeature(const Feature& feature, std::uint32_t index, const Building& values,
                    const std::string& where, FootprintTriangulator& triangulator,
                    std::vector<Building>& out) {
    for (std::uint32_t part = 0; part < feature.parts.size(); ++part) {
        const std::vector<glm::dvec2>& ring = feature.parts[part];
        if (ring.size() < 4) {
            return Error{where + "a footprint ring has fewer than three corners"};
        }
        if (signedArea(ring) > 0.0 || out.empty() || out.back().feature != index) {
            Building building = values;
            building.feature = index;
            glm::dvec2 sum(0.0);
            for (std::size_t i = 0; i + 1 < ring.size(); ++i) {
                sum += ring[i];
            }
            building.reference = sum / double(ring.size() - 1);
            out.push_back(std::move(building));
        }
        out.back().rings.push_back(part);
    }
    for (auto it = out.rbegin(); it != out.rend() && it->feature == index; ++it) {
        const LocalPlane plane(it->reference.y, it->reference.x);
        const std::string reason = triangulator.invalidReason(localRings(feature, *it, plane));
        if (!reason.empty()) {
            return Error{where + "the footprint is not a valid polygon: " + reason};
        }
    }
    return Status::success();
}

}  // namespace

Result<std::shared_ptr<const BuildingsSource::Prepared>> BuildingsSource::prepared() const {
    std::lock_guard lock(mutex_);
    if (prepared_) {
        return prepared_;
    }
    if (failure_) {
        return *failure_;
    }
    auto fail = [&](Error error) {
        error.message = "buildings '" + name() + "': " + error.message;
        failure_ = error;
        return error;
    };
    Result<std::shared_ptr<const FeatureCollection>> collection = features_->collection();
    if (!collection) {
        return fail(collection.error());
    }
    auto result = std::make_shared<Prepared>();
    result->collection = collection.value();
    BuildingReader reader(*result->collection, *features_, parameters_);
    if (Status status = reader.resolveFields(); !status) {
        return fail(status.error());
    }
    FootprintTriangulator triangulator;
    const FeatureValues values(*result->collection, features_->file().string());
    const std::vector<Feature>& features = result->collection->features();
    for (std::uint32_t i = 0; i < features.size(); ++i) {
        Building building;
        if (Status status = reader.read(features[i], building); !status) {
            return fail(status.error());
        }
        if (Status status = splitFeature(features[i], i, building, values.where(features[i]),
                                         triangulator, result->buildings);
            !status) {
            return fail(status.error());
        }
        result->bounds.extend(features[i].bounds);
    }
    for (std::uint32_t b = 0; b < result->buildings.size(); ++b) {
        result->byTile[MeshSource::keyOf(result->buildings[b].reference)].push_back(b);
    }
    prepared_ = result;
    return prepared_;
}

Result<GeographicBounds> BuildingsSource::bounds() const {
    Result<std::shared_ptr<const Prepared>> p = prepared();
    if (!p) {
        return p.error();
    }
    return p.value()->bounds;
}

Result<std::vector<TileKey>> BuildingsSource::tileKeys() const {
    Result<std::shared_ptr<const Prepared>> p = prepared();
    if (!p) {
        return p.error();
    }
    std::vector<TileKey> keys;
    for (const auto& [key, buildings] : p.value()->byTile) {
        keys.push_back(key);
    }
    return keys;
}

namespace {

// Lowest and mean ground height under a footprint: at every vertex, every edge midpoint
// and the centroid of the outer ring.
Result<glm::dvec2> groundUnder(const std::vector<Ring>& rings, const LocalPlane& plane,
                               GroundSampler& ground) {
    std::vector<glm::dvec2> samples;
    for (const Ring& ring : rings) {
        for (std::size_t i = 0; i < ring.size(); ++i) {
            samples.push_back(ring[i]);
            samples.push_back(0.5 * (ring[i] + ring[(i + 1) % ring.size()]));
        }
    }
    glm::dvec2 mean(0.0);
    for (const glm::dvec2& p : rings.front()) {
        mean += p / double(rings.front().size());
    }
    samples.push_back(mean);
    double lowest = std::numeric_limits<double>::infinity(), sum = 0.0;
    for (const glm::dvec2& sample : samples) {
        const glm::dvec2 lonLat = plane.toLongitudeLatitude(sample);
        Result<double> height = ground.heightAt(lonLat.y, lonLat.x);
        if (!height) {
            return height.error();
        }
        lowest = std::min(lowest, height.value());
        sum += height.value();
    }
    return glm::dvec2(lowest, sum / double(samples.size()));
}

void computeBounds(MeshTile& tile) {
    glm::dvec3 low(std::numeric_limits<double>::infinity()), high(-low);
    for (const MeshVertex& v : tile.geometry.vertices) {
        low = glm::min(low, glm::dvec3(v.position));
        high = glm::max(high, glm::dvec3(v.position));
    }
    if (tile.geometry.vertices.empty()) {
        low = high = glm::dvec3(0.0);
    }
    tile.boundsCenter = tile.origin + 0.5 * (low + high);
    tile.boundsRadius = 0.5 * glm::length(high - low);
}

}  // namespace

Result<std::shared_ptr<const MeshTile>> BuildingsSource::tile(const TileKey& key,
                                                              TileProvider& provider) const {
    Result<std::shared_ptr<const Prepared>> p = prepared();
    if (!p) {
        return p.error();
    }
    auto tile = std::make_shared<MeshTile>();
    tile->key = key;
    const double latitude = 0.5 * (key.north() + key.south());
    const double longitude = 0.5 * (key.west() + key.east());
    tile->origin = Ellipsoid::toEcef(Geodetic{latitude, longitude, 0.0});
    const auto found = p.value()->byTile.find(key);
    if (found == p.value()->byTile.end()) {
        return std::shared_ptr<const MeshTile>(tile);
    }
    GroundSampler ground(*elevation_, provider, kGroundLevel);
    BuildingExtruder extruder;
    const std::vector<Feature>& features = p.value()->collection->features();
    for (std::uint32_t index : found->second) {
        const Building& building = p.value()->buildings[index];
        const Feature& feature = features[building.feature];
        const LocalPlane plane(building.reference.y, building.reference.x);
        BuildingShape shape;
        shape.rings = localRings(feature, building, plane);
        Result<glm::dvec2> groundHeights = groundUnder(shape.rings, plane, ground);
        if (!groundHeights) {
            return Error{"buildings '" + name() + "': " + groundHeights.error().message};
        }
        const double base =
            parameters_.meanBase ? groundHeights.value().y : groundHeights.value().x;
        shape.bottom = groundHeights.value().x - kWallSkirt;
        shape.eaves = base + building.height;
        shape.roof = building.roof;
        shape.pitch = building.pitch;
        shape.wallColor = building.wallColor;
        shape.roofColor = building.roofColor;
        if (Status status = extruder.append(shape, plane, tile->origin, tile->geometry); !status) {
            return Error{"buildings '" + name() + "': " + features_->file().string() +
                         ": feature " + std::to_string(feature.id) + ": " + status.error().message};
        }
        ++tile->featureCount;
    }
    computeBounds(*tile);
    return std::shared_ptr<const MeshTile>(tile);
}

namespace {

Result<BuildingsParameters> readParameters(const BlockReader& reader) {
    BuildingsParameters p;
    p.height = reader.optionalNumber("height").value_or(p.height);
    p.heightAttribute = reader.string("height_attribute");
    p.floorsAttribute = reader.string("floors_attribute");
    p.storeyHeight = reader.optionalNumber("storey_height").value_or(p.storeyHeight);
    if (const Value* base = reader.value("base"); base != nullptr && base->get<Word>()) {
        p.meanBase = base->get<Word>()->text == "mean";
    }
    if (const Value* roof = reader.value("roof"); roof != nullptr && roof->get<Word>()) {
        p.roof = roof->get<Word>()->text;
    }
    p.roofAttribute = reader.string("roof_attribute");
    p.pitch = reader.optionalNumber("roof_pitch").value_or(p.pitch);
    p.pitchAttribute = reader.string("pitch_attribute");
    if (std::optional<Color> c = reader.color("wall_color")) {
        p.wallColor = {c->r, c->g, c->b};
    }
    if (std::optional<Color> c = reader.color("roof_color")) {
        p.roofColor = {c->r, c->g, c->b};
    }
    p.wallColorAttribute = reader.string("wall_color_attribute");
    p.roofColorAttribute = reader.string("roof_color_attribute");
    return p;
}

}  // namespace

Result<std::unique_ptr<Source>> BuildingsSource::create(const SourceBuildContext& context) {
    Result<MeshInputs> inputs = readMeshInputs(context);
    if (!inputs) {
        return inputs.error();
    }
    Result<BuildingsParameters> parameters = readParameters(context.reader);
    if (!parameters) {
        return parameters.error();
    }
    return std::unique_ptr<Source>(std::make_unique<BuildingsSource>(
        context.block.name, inputs->features, inputs->elevation, std::move(parameters.value())));
}

}  // namespace sylva
