#include "sylva/core/sources/vector/ElevationEditSource.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "sylva/core/base/Hash.h"
#include "sylva/core/geo/Ellipsoid.h"
#include "sylva/core/sources/GroundSampler.h"
#include "sylva/core/sources/vector/CoverageRasterizer.h"

namespace sylva {
namespace {

double smoothstep(double t) {
    t = std::clamp(t, 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}

// Area centroid of the oriented rings (holes subtract), longitude/latitude.
glm::dvec2 centroid(const Feature& feature) {
    double area = 0.0;
    glm::dvec2 sum(0.0);
    for (const std::vector<glm::dvec2>& ring : feature.parts) {
        for (std::size_t i = 0; i + 1 < ring.size(); ++i) {
            const double cross = ring[i].x * ring[i + 1].y - ring[i + 1].x * ring[i].y;
            area += cross;
            sum += (ring[i] + ring[i + 1]) * cross;
        }
    }
    if (std::abs(area) < 1e-30) {
        return {0.5 * (feature.bounds.west + feature.bounds.east),
                0.5 * (feature.bounds.south + feature.bounds.north)};
    }
    return sum / (3.0 * area);
}

using Mode = ElevationEditParameters::Mode;

// The edit's value for one feature: its attribute when one is named, else the default.
Result<double> editValue(const Feature& feature, std::optional<std::size_t> field,
                         const std::string& attribute, double fallback, const std::string& file) {
    if (!field) {
        return fallback;
    }
    const std::string& text = feature.attributes[*field];
    char* end = nullptr;
    const double value = std::strtod(text.c_str(), &end);
    if (text.empty() || *end != '\0' || !std::isfinite(value)) {
        return Error{file + ": feature " + std::to_string(feature.id) + ": attribute '" +
                     attribute + "' is not a number: '" + text + "'"};
    }
    return value;
}

// One polygon applied to the tile: its value, its boundary (for the feather) and its
// slope plane's anchor.
class PolygonEdit {
public:
    PolygonEdit(const ElevationEditParameters& parameters, const CoverageRasterizer& rasterizer,
                const FeatureHit& hit, double value)
        : parameters_(parameters),
          rasterizer_(rasterizer),
          shift_(hit.longitudeShift),
          value_(value),
          anchor_(centroid(*hit.feature)),
          anchorEast_(Ellipsoid::primeVerticalRadius(anchor_.y) * std::cos(anchor_.y)),
          anchorNorth_(Ellipsoid::meridionalRadius(anchor_.y)) {
        // Edges in grid coordinates for the distance to the boundary.
        if (parameters_.feather > 0.0) {
            for (const std::vector<glm::dvec2>& ring : hit.feature->parts) {
                for (std::size_t i = 0; i + 1 < ring.size(); ++i) {
                    edges_.emplace_back(rasterizer.toGrid(ring[i], shift_),
                                        rasterizer.toGrid(ring[i + 1], shift_));
                }
            }
        }
    }

    // The weight at a texel centre: 1 inside, else the area coverage or (with feather)
    // the smoothstep of the distance to the nearest edge, in metres (`k`: metres per
    // grid unit).
    double weight(const glm::dvec2& centre, const glm::dvec2& k, double coverage) const {
        if (edges_.empty() || !(coverage < 1.0)) {
            return coverage;
        }
        int winding = 0;
        double nearest = 1e300;
        for (const auto& [p, q] : edges_) {
            // Grid y grows southwards; the winding sign does not matter here.
            if (p.y <= centre.y) {
                if (q.y > centre.y &&
                    (q.x - p.x) * (centre.y - p.y) - (centre.x - p.x) * (q.y - p.y) > 0) {
                    ++winding;
                }
            } else if (q.y <= centre.y &&
                       (q.x - p.x) * (centre.y - p.y) - (centre.x - p.x) * (q.y - p.y) < 0) {
                --winding;
            }
            const glm::dvec2 d = (q - p) * k, r = (centre - p) * k;
            const double dd = glm::dot(d, d);
            const double t = dd > 0.0 ? std::clamp(glm::dot(r, d) / dd, 0.0, 1.0) : 0.0;
            nearest = std::min(nearest, glm::length(r - t * d));
        }
        return winding != 0 ? 1.0
                            : std::max(coverage, smoothstep(1.0 - nearest / parameters_.feather));
    }

    // h = h0 + w (target - h0), or h0 ± w amount.
    float apply(float h, double weight, const glm::dvec2& centre) const {
        switch (parameters_.mode) {
            case Mode::Flatten:
            case Mode::Level:
                return static_cast<float>(h + weight * (value_ - h));
            case Mode::Raise:
                return static_cast<float>(h + weight * value_);
            case Mode::Lower:
                return static_cast<float>(h - weight * value_);
            case Mode::Slope: {
                const glm::dvec2 lonLat = rasterizer_.toLonLat(centre);
                const double east = (lonLat.x - shift_ - anchor_.x) * anchorEast_;
                const double north = (lonLat.y - anchor_.y) * anchorNorth_;
                const double plane =
                    value_ + parameters_.gradient * (east * std::sin(parameters_.direction) +
                                                     north * std::cos(parameters_.direction));
                return static_cast<float>(h + weight * (plane - h));
            }
        }
        return h;
    }

private:
    const ElevationEditParameters& parameters_;
    const CoverageRasterizer& rasterizer_;
    double shift_;
    double value_;
    glm::dvec2 anchor_;
    double anchorEast_, anchorNorth_;
    std::vector<std::pair<glm::dvec2, glm::dvec2>> edges_;
};

}  // namespace

ElevationEditSource::ElevationEditSource(std::string name, const Source* input,
                                         const FeatureSource* features,
                                         ElevationEditParameters parameters)
    : Source(std::move(name), "elevation_edit", PortType::Elevation, 1),
      input_(input),
      features_(features),
      parameters_(std::move(parameters)) {
    addInput(input_);
    addInput(features_);
    ContentHash hash;
    hash.add(static_cast<int>(parameters_.mode)).add(parameters_.height).add(parameters_.amount);
    hash.add(parameters_.gradient).add(parameters_.direction).add(parameters_.feather);
    hash.add(parameters_.heightAttribute).add(parameters_.amountAttribute);
    setParameterHash(hash.value());
}

Result<TilePointer> ElevationEditSource::produce(const TileKey& key, TileProvider& provider) const {
    Result<TilePointer> base = provider.tile(*input_, key);
    if (!base) {
        return base.error();
    }
    Result<std::shared_ptr<const FeatureCollection>> loaded = features_->collection();
    if (!loaded) {
        return loaded.error();
    }
    const FeatureCollection& collection = *loaded.value();
    const std::string file = features_->file().string();
    const bool usesHeight = parameters_.mode == Mode::Flatten || parameters_.mode == Mode::Slope;
    const std::string& attribute =
        usesHeight ? parameters_.heightAttribute : parameters_.amountAttribute;
    std::optional<std::size_t> field;
    if (!attribute.empty()) {
        field = collection.field(attribute);
        if (!field) {
            return Error{file + ": no attribute '" + attribute + "' (for source '" + name() + "')"};
        }
    }
    const TileFormat& format = provider.format();
    const CoverageRasterizer rasterizer(key, format.size, format.border);
    const int w = rasterizer.width();
    auto tile = std::make_shared<ImageTile>(*base.value());
    // Reach of the feather in longitude/latitude, at the tile's poleward edge.
    const double poleward =
        std::min(std::max(std::abs(key.north()), std::abs(key.south())), 1.5707);
    const double reachLatitude = parameters_.feather / Ellipsoid::meridionalRadius(0.0);
    const double reachLongitude =
        parameters_.feather / (Ellipsoid::primeVerticalRadius(poleward) * std::cos(poleward));
    const double marginX = (format.border + 1) * tile->texelWidth() + reachLongitude;
    const double marginY = (format.border + 1) * tile->texelHeight() + reachLatitude;
    const GeographicBounds window{key.west() - marginX, key.south() - marginY, key.east() + marginX,
                                  key.north() + marginY};
    std::vector<float> coverage;
    for (const FeatureHit& hit : collection.query(window)) {
        const Feature& feature = *hit.feature;
        if (feature.kind != GeometryKind::Polygon) {
            return Error{file + ": feature " + std::to_string(feature.id) +
                         ": elevation_edit takes polygons, not points or lines"};
        }
        Result<double> value = editValue(
            feature, field, attribute, usesHeight ? parameters_.height : parameters_.amount, file);
        if (!value) {
            return value.error();
        }
        if (parameters_.mode == Mode::Level) {
            Result<double> ground = meanHeightUnder(feature, provider);
            if (!ground) {
                return ground.error();
            }
            value = ground.value() + value.value();
        }
        rasterizer.fillPolygon(feature.parts, hit.longitudeShift, coverage);
        // Texel range touched: the feature's bounds grown by the feather.
        const glm::dvec2 a = rasterizer.toGrid(
            {feature.bounds.west - reachLongitude, feature.bounds.north + reachLatitude},
            hit.longitudeShift);
        const glm::dvec2 b = rasterizer.toGrid(
            {feature.bounds.east + reachLongitude, feature.bounds.south - reachLatitude},
            hit.longitudeShift);
        const int x0 = std::max(0, static_cast<int>(std::floor(a.x))),
                  x1 = std::min(w - 1, static_cast<int>(b.x));
        const int y0 = std::max(0, static_cast<int>(std::floor(a.y))),
                  y1 = std::min(w - 1, static_cast<int>(b.y));
        const PolygonEdit edit(parameters_, rasterizer, hit, *value);
        for (int gy = y0; gy <= y1; ++gy) {
            const glm::dvec2 k = rasterizer.metresPerTexel(gy + 0.5);
            for (int gx = x0; gx <= x1; ++gx) {
                const glm::dvec2 centre(gx + 0.5, gy + 0.5);
                const double weight = edit.weight(centre, k, coverage[std::size_t(gy) * w + gx]);
                if (weight <= 0.0) {
                    continue;
                }
                float& h = tile->at(gx - format.border, gy - format.border, 0);
                h = edit.apply(h, weight, centre);
            }
        }
    }
    return TilePointer(std::move(tile));
}

Result<double> ElevationEditSource::meanHeightUnder(const Feature& feature,
                                                    TileProvider& provider) const {
    GroundSampler ground(*input_, provider, kLevelSampleLevel);
    double sum = 0.0;
    int count = 0;
    const auto add = [&](const glm::dvec2& point) -> Status {
        Result<double> height = ground.heightAt(point.y, point.x);
        if (!height) {
            return height.error();
        }
        sum += height.value();
        ++count;
        return Status::success();
    };
    for (const std::vector<glm::dvec2>& ring : feature.parts) {
        for (std::size_t i = 0; i + 1 < ring.size(); ++i) {
            if (Status status = add(ring[i]); !status) {
                return status.error();
            }
        }
    }
    if (Status status = add(centroid(feature)); !status) {
        return status.error();
    }
    return sum / count;
}

Result<std::unique_ptr<Source>> ElevationEditSource::create(const SourceBuildContext& context) {
    const BlockReader& reader = context.reader;
    Result<const Source*> input = context.input("input", true);
    if (!input) {
        return input.error();
    }
    Result<const Source*> features = context.input("features", true);
    if (!features) {
        return features.error();
    }
    if (input.value()->output() != PortType::Elevation) {
        return Error{reader.where("input") + "'input' must be an elevation, but source '" +
                     input.value()->name() + "' gives " + portTypeName(input.value()->output())};
    }
    const FeatureSource* featureSource = FeatureSource::from(features.value());
    if (featureSource == nullptr) {
        return Error{reader.where("features") + "'features' must be a features source"};
    }
    ElevationEditParameters p;
    if (const Value* v = reader.value("mode")) {
        if (const Word* word = v->get<Word>()) {
            using Mode = ElevationEditParameters::Mode;
            p.mode = word->text == "raise"   ? Mode::Raise
                     : word->text == "lower" ? Mode::Lower
                     : word->text == "slope" ? Mode::Slope
                     : word->text == "level" ? Mode::Level
                                             : Mode::Flatten;
        }
    }
    p.height = reader.optionalNumber("height").value_or(0.0);
    p.amount = reader.optionalNumber("amount").value_or(0.0);
    p.gradient = reader.optionalNumber("gradient").value_or(0.0);
    p.direction = reader.optionalNumber("direction").value_or(0.0);
    p.feather = reader.optionalNumber("feather").value_or(0.0);
    p.heightAttribute = reader.string("height_attribute");
    p.amountAttribute = reader.string("amount_attribute");
    return std::unique_ptr<Source>(std::make_unique<ElevationEditSource>(
        context.block.name, input.value(), featureSource, std::move(p)));
}

}  // namespace sylva
