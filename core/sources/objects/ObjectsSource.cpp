#include "sylva/core/sources/objects/ObjectsSource.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "FeatureValues.h"
#include "sylva/core/base/Hash.h"
#include "sylva/core/geo/Ellipsoid.h"
#include "sylva/core/sources/GroundSampler.h"
#include "sylva/core/sources/objects/ModelImporter.h"

namespace sylva {

namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

// A placement before the terrain is known.
struct Placement {
    glm::dvec2 point{0.0};  // longitude, latitude (radians)
    double heading = 0.0;   // radians clockwise from north
    double scale = 1.0;
    double height = 0.0;  // above the terrain, or absolute
    std::vector<float> partAngles;
    std::int64_t featureId = -1;
};

// The azimuth (clockwise from north) from `from` to `to` in the local frame of `from`.
double azimuth(const glm::dvec2& from, const glm::dvec2& to) {
    const glm::dmat3 frame = Ellipsoid::localFrame(from.y, from.x);
    const glm::dvec3 d = Ellipsoid::toEcef(Geodetic{to.y, to.x, 0.0}) -
                         Ellipsoid::toEcef(Geodetic{from.y, from.x, 0.0});
    return std::atan2(glm::dot(d, frame[0]), glm::dot(d, frame[1]));
}

// Points every `spacing` metres along a line (starting at its first vertex), each with
// the azimuth of the segment it lies on.
std::vector<std::pair<glm::dvec2, double>> alongLine(const std::vector<glm::dvec2>& line,
                                                     double spacing) {
    std::vector<std::pair<glm::dvec2, double>> out;
    double carried = 0.0;  // distance from the last placement to the segment start
    for (std::size_t i = 0; i + 1 < line.size(); ++i) {
        const glm::dvec2 a = line[i], b = line[i + 1];
        const double metresEast = Ellipsoid::primeVerticalRadius(a.y) * std::cos(a.y);
        const double metresNorth = Ellipsoid::meridionalRadius(a.y);
        const double length =
            glm::length(glm::dvec2((b.x - a.x) * metresEast, (b.y - a.y) * metresNorth));
        const double direction = azimuth(a, b);
        double along = i == 0 ? 0.0 : spacing - carried;
        for (; along <= length + 1e-9; along += spacing) {
            out.emplace_back(length > 0 ? a + (b - a) * (along / length) : a, direction);
        }
        carried = length - (along - spacing);
    }
    return out;
}

}  // namespace

struct ObjectsSource::Prepared {
    std::shared_ptr<const MeshModel> model;
    std::vector<Placement> placements;
    std::map<TileKey, std::vector<std::uint32_t>> byTile;
    GeographicBounds bounds = GeographicBounds::empty();
};

ObjectsSource::ObjectsSource(std::string name, const FeatureSource* features,
                             const Source* elevation, ObjectsParameters parameters)
    : MeshSource(std::move(name), "objects"),
      features_(features),
      elevation_(elevation),
      parameters_(std::move(parameters)) {
    addInput(features_);
    addInput(elevation_);
    const ObjectsParameters& p = parameters_;
    ContentHash hash;
    hash.add(p.model.string());
    std::error_code error;
    const auto size = std::filesystem::file_size(p.model, error);
    hash.add(std::uint64_t(error ? 0 : size));
    const auto time = std::filesystem::last_write_time(p.model, error);
    hash.add(std::int64_t(error ? 0 : time.time_since_epoch().count()));
    hash.add(p.scale).add(p.scaleAttribute).add(p.sizeAttribute).add(p.referenceHeight);
    hash.add(p.heading).add(p.headingAttribute).add(p.faceToward.has_value());
    if (p.faceToward) {
        hash.add(p.faceToward->latitude).add(p.faceToward->longitude);
    }
    hash.add(p.height).add(p.heightAttribute).add(p.absolute).add(p.spacing);
    for (const auto& [node, attribute] : p.partAttributes) {
        hash.add(node).add(attribute);
    }
    for (const auto& [node, angle] : p.partAngles) {
        hash.add(node).add(angle);
    }
    setParameterHash(hash.value());
}

ObjectsSource::~ObjectsSource() = default;

namespace {

// Per-feature values of the placements (scale, heading, height, part angles).
class PlacementReader {
public:
    PlacementReader(const FeatureCollection& collection, const FeatureSource& features,
                    const ObjectsParameters& parameters, const MeshModel& model)
        : values_(collection, features.file().string()), parameters_(parameters), model_(model) {}

    Status resolveFields() {
        for (auto [attribute, slot] : {std::pair{&parameters_.scaleAttribute, &scale_},
                                       std::pair{&parameters_.sizeAttribute, &size_},
                                       std::pair{&parameters_.headingAttribute, &heading_},
                                       std::pair{&parameters_.heightAttribute, &height_}}) {
            Result<std::optional<std::size_t>> field = values_.field(*attribute);
            if (!field) {
                return field.error();
            }
            *slot = field.value();
        }
        std::string nodes;
        for (const ModelPart& part : model_.parts) {
            nodes += (nodes.empty() ? "" : ", ") + part.name;
        }
        const auto partIndex = [&](const std::string& node) -> Result<int> {
            const int index = model_.findPart(node);
            if (index < 0) {
                return Error{model_.file + ": no node named '" + node + "' (nodes: " + nodes + ")"};
            }
            return index;
        };
        baseAngles_.assign(model_.parts.size(), 0.0f);
        for (const auto& [node, angle] : parameters_.partAngles) {
            Result<int> index = partIndex(node);
            if (!index) {
                return index.error();
            }
            baseAngles_[std::size_t(index.value())] = float(angle);
        }
        for (const auto& [node, attribute] : parameters_.partAttributes) {
            Result<int> index = partIndex(node);
            if (!index) {
                return index.error();
            }
            Result<std::optional<std::size_t>> field = values_.field(attribute);
            if (!field) {
                return field.error();
            }
            parts_.emplace_back(index.value(), *field.value());
        }
        return Status::success();
    }

    // The feature's placement values (its point(s) are filled in by the caller).
    Status read(const Feature& feature, Placement& placement) const {
        placement.featureId = feature.id;
        placement.scale = parameters_.scale;
        placement.heading = parameters_.heading;
        placement.height = parameters_.height;
        const auto number = [&](std::optional<std::size_t> field, double& out,
                                double factor) -> Status {
            if (!field) {
                return Status::success();
            }
            Result<double> value = values_.number(feature, *field);
            if (!value) {
                return value.error();
            }
            out = value.value() * factor;
            return Status::success();
        };
        for (Status status : {number(scale_, placement.scale, 1.0),
                              number(size_, placement.scale, 1.0 / parameters_.referenceHeight),
                              number(heading_, placement.heading, kDegree),
                              number(height_, placement.height, 1.0)}) {
            if (!status) {
                return status;
            }
        }
        if (!(placement.scale > 0.0)) {
            return Error{values_.where(feature) + "the scale must be positive"};
        }
        placement.partAngles = baseAngles_;
        for (const auto& [index, field] : parts_) {
            Result<double> angle = values_.number(feature, field);
            if (!angle) {
                return angle.error();
            }
            placement.partAngles[std::size_t(index)] = float(angle.value() * kDegree);
        }
        return Status::success();
    }

    std::string where(const Feature& feature) const { return values_.where(feature); }

private:
    FeatureValues values_;
    const ObjectsParameters& parameters_;
    const MeshModel& model_;
    std::optional<std::size_t> scale_, size_, heading_, height_;
    std::vector<std::pair<int, std::size_t>> parts_;  // part index, field
    std::vector<float> baseAngles_;
};

}  // namespace

Result<std::shared_ptr<const ObjectsSource::Prepared>> ObjectsSource::prepared() const {
    std::lock_guard lock(mutex_);
    if (prepared_) {
        return prepared_;
    }
    if (failure_) {
        return *failure_;
    }
    auto fail = [&](Error error) {
        error.message = "objects '" + name() + "': " + error.message;
        failure_ = error;
        return error;
    };
    auto result = std::make_shared<Prepared>();
    Result<std::shared_ptr<const MeshModel>> model = importModel(parameters_.model);
    if (!model) {
        return fail(model.error());
    }
    result->model = model.value();
    Result<std::shared_ptr<const FeatureCollection>> collection = features_->collection();
    if (!collection) {
        return fail(collection.error());
    }
    PlacementReader reader(*collection.value(), *features_, parameters_, *result->model);
    if (Status status = reader.resolveFields(); !status) {
        return fail(status.error());
    }
    const std::optional<glm::dvec2> toward =
        parameters_.faceToward ? std::optional(glm::dvec2(parameters_.faceToward->longitude,
                                                          parameters_.faceToward->latitude))
                               : std::nullopt;
    for (const Feature& feature : collection.value()->features()) {
        Placement values;
        if (Status status = reader.read(feature, values); !status) {
            return fail(status.error());
        }
        if (feature.kind == GeometryKind::Polygon) {
            return fail(Error{reader.where(feature) +
                              "objects are placed on points or along lines, not on polygons"});
        }
        for (const std::vector<glm::dvec2>& part : feature.parts) {
            std::vector<std::pair<glm::dvec2, double>> points;
            if (feature.kind == GeometryKind::Point) {
                for (const glm::dvec2& point : part) {
                    points.emplace_back(point, 0.0);
                }
            } else {
                points = alongLine(part, parameters_.spacing);
            }
            for (const auto& [point, direction] : points) {
                Placement placement = values;
                placement.point = point;
                placement.heading = toward ? azimuth(point, *toward) : values.heading + direction;
                result->placements.push_back(std::move(placement));
            }
        }
        result->bounds.extend(feature.bounds);
    }
    for (std::uint32_t i = 0; i < result->placements.size(); ++i) {
        result->byTile[keyOf(result->placements[i].point)].push_back(i);
    }
    prepared_ = result;
    return prepared_;
}

Result<GeographicBounds> ObjectsSource::bounds() const {
    Result<std::shared_ptr<const Prepared>> p = prepared();
    if (!p) {
        return p.error();
    }
    return p.value()->bounds;
}

Result<std::shared_ptr<const MeshTile>> ObjectsSource::tile(const TileKey& key,
                                                            TileProvider& provider) const {
    Result<std::shared_ptr<const Prepared>> p = prepared();
    if (!p) {
        return p.error();
    }
    auto tile = std::make_shared<MeshTile>();
    tile->key = key;
    tile->origin = Ellipsoid::toEcef(
        Geodetic{0.5 * (key.north() + key.south()), 0.5 * (key.west() + key.east()), 0.0});
    const auto found = p.value()->byTile.find(key);
    if (found == p.value()->byTile.end()) {
        return std::shared_ptr<const MeshTile>(tile);
    }
    tile->model = p.value()->model;
    const MeshModel& model = *tile->model;
    GroundSampler ground(*elevation_, provider, kGroundLevel);
    glm::dvec3 sum(0.0);
    for (std::uint32_t index : found->second) {
        const Placement& placement = p.value()->placements[index];
        double height = placement.height;
        if (!parameters_.absolute) {
            Result<double> terrain = ground.heightAt(placement.point.y, placement.point.x);
            if (!terrain) {
                return Error{"objects '" + name() + "': " + terrain.error().message};
            }
            height += terrain.value();
        }
        ModelPlacement out;
        out.position = Ellipsoid::toEcef(Geodetic{placement.point.y, placement.point.x, height});
        const glm::dmat3 frame = Ellipsoid::localFrame(placement.point.y, placement.point.x);
        const double s = std::sin(placement.heading), c = std::cos(placement.heading);
        out.axes = glm::dmat3(c * frame[0] - s * frame[1], s * frame[0] + c * frame[1], frame[2]) *
                   placement.scale;
        out.partAngles = placement.partAngles;
        out.featureId = placement.featureId;
        sum += out.position;
        tile->placements.push_back(std::move(out));
    }
    tile->boundsCenter = sum / double(tile->placements.size());
    for (const ModelPlacement& placement : tile->placements) {
        const double reach = glm::length(placement.position - tile->boundsCenter) +
                             glm::length(placement.axes * model.boundsCenter) +
                             model.boundsRadius * glm::length(placement.axes[0]);
        tile->boundsRadius = std::max(tile->boundsRadius, reach);
    }
    tile->featureCount = tile->placements.size();
    return std::shared_ptr<const MeshTile>(tile);
}

namespace {

Result<ObjectsParameters> readParameters(const SourceBuildContext& context) {
    const BlockReader& reader = context.reader;
    ObjectsParameters p;
    const std::filesystem::path model = reader.string("model");
    p.model = model.is_absolute() ? model : context.projectFolder / model;
    p.scale = reader.optionalNumber("scale").value_or(1.0);
    p.scaleAttribute = reader.string("scale_attribute");
    p.sizeAttribute = reader.string("size_attribute");
    p.referenceHeight = reader.optionalNumber("reference_height").value_or(1.0);
    p.heading = reader.optionalNumber("heading").value_or(0.0);
    p.headingAttribute = reader.string("heading_attribute");
    p.faceToward = reader.geo("face_toward");
    p.height = reader.optionalNumber("height").value_or(0.0);
    p.heightAttribute = reader.string("height_attribute");
    if (const Value* mode = reader.value("height_mode"); mode != nullptr && mode->get<Word>()) {
        p.absolute = mode->get<Word>()->text == "absolute";
    }
    p.spacing = reader.optionalNumber("spacing").value_or(50.0);
    if (const Value* parts = reader.value("parts")) {
        if (const ValueObject* object = parts->get<ValueObject>()) {
            for (const auto& [node, value] : *object) {
                const std::string* attribute = value.get<std::string>();
                const Word* word = value.get<Word>();
                if (attribute == nullptr && word == nullptr) {
                    return Error{reader.where("parts") + "part '" + node +
                                 "' must name an attribute (a string)"};
                }
                p.partAttributes.emplace_back(node, attribute ? *attribute : word->text);
            }
        }
    }
    if (const Value* angles = reader.value("part_angles")) {
        if (const ValueObject* object = angles->get<ValueObject>()) {
            for (const auto& [node, value] : *object) {
                const Quantity* angle = value.get<Quantity>();
                if (angle == nullptr) {
                    return Error{reader.where("part_angles") + "part '" + node +
                                 "' needs an angle (e.g. 20deg)"};
                }
                p.partAngles.emplace_back(node, angle->value);
            }
        }
    }
    return p;
}

}  // namespace

Result<std::unique_ptr<Source>> ObjectsSource::create(const SourceBuildContext& context) {
    Result<MeshInputs> inputs = readMeshInputs(context);
    if (!inputs) {
        return inputs.error();
    }
    Result<ObjectsParameters> parameters = readParameters(context);
    if (!parameters) {
        return parameters.error();
    }
    return std::unique_ptr<Source>(std::make_unique<ObjectsSource>(
        context.block.name, inputs->features, inputs->elevation, std::move(parameters.value())));
}

}  // namespace sylva
