#include "sylva/core/sources/compose/RasterizeSource.h"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "sylva/core/base/Hash.h"
#include "sylva/core/image/ColorSpace.h"
#include "sylva/core/sources/vector/CoverageRasterizer.h"

namespace sylva {

RasterizeSource::RasterizeSource(std::string name, const FeatureSource* features,
                                 const PlantsSource* instances, RasterizeParameters parameters)
    : Source(std::move(name), "rasterize", parameters.image ? PortType::Image : PortType::Mask,
             parameters.image ? 4 : 1),
      features_(features),
      instances_(instances),
      parameters_(std::move(parameters)) {
    SYLVA_CHECK((features_ == nullptr) != (instances_ == nullptr));
    addInput(features_ != nullptr ? static_cast<const Source*>(features_) : instances_);
    ContentHash hash;
    hash.add(parameters_.image)
        .add(parameters_.fill)
        .add(parameters_.outline)
        .add(parameters_.lineWidth);
    hash.add(parameters_.pointRadius)
        .add(parameters_.minimumTexels)
        .add(parameters_.color.r)
        .add(parameters_.color.g)
        .add(parameters_.color.b);
    hash.add(parameters_.opacity).add(parameters_.colorAttribute);
    for (const auto& [value, c] : parameters_.colors) {
        hash.add(value).add(c.r).add(c.g).add(c.b);
    }
    setParameterHash(hash.value());
}

std::optional<glm::vec3> RasterizeSource::parseHexColor(const std::string& text) {
    std::string hex = text;
    if (!hex.empty() && hex.front() == '#') {
        hex.erase(0, 1);
    }
    if (hex.size() == 3) {
        hex = {hex[0], hex[0], hex[1], hex[1], hex[2], hex[2]};
    }
    if (hex.size() != 6 || !std::all_of(hex.begin(), hex.end(), [](char c) {
            return std::isxdigit(static_cast<unsigned char>(c));
        })) {
        return std::nullopt;
    }
    glm::vec3 out;
    for (int i = 0; i < 3; ++i) {
        const int value = std::stoi(hex.substr(std::size_t(i) * 2, 2), nullptr, 16);
        out[i] = srgbToLinear(static_cast<float>(value) / 255.0f);
    }
    return out;
}

Result<TilePointer> RasterizeSource::produce(const TileKey& key, TileProvider& provider) const {
    const TileFormat& format = provider.format();
    const CoverageRasterizer rasterizer(key, format.size, format.border);
    const int w = rasterizer.width();
    const std::size_t texels = std::size_t(w) * w;
    // Premultiplied accumulation: colour x alpha and alpha.
    std::vector<glm::vec3> colour(parameters_.image ? texels : 0, glm::vec3(0.0f));
    std::vector<float> alpha(texels, 0.0f);
    auto composite = [&](const std::vector<float>& coverage, const glm::vec3& c) {
        for (std::size_t i = 0; i < texels; ++i) {
            const float a = coverage[i] * static_cast<float>(parameters_.opacity);
            if (a <= 0.0f) {
                continue;
            }
            if (parameters_.image) {
                colour[i] = c * a + colour[i] * (1.0f - a);
            }
            alpha[i] = a + alpha[i] * (1.0f - a);
        }
    };
    std::vector<float> coverage, strokes;
    const double minimumWidth = parameters_.minimumTexels * rasterizer.metresPerTexel(0.5 * w).y;
    const double outlineWidth =
        parameters_.outline > 0.0 ? std::max(parameters_.outline, minimumWidth) : 0.0;
    const double lineWidth =
        parameters_.lineWidth > 0.0 ? std::max(parameters_.lineWidth, minimumWidth) : 0.0;
    if (features_ != nullptr) {
        Result<std::shared_ptr<const FeatureCollection>> loaded = features_->collection();
        if (!loaded) {
            return loaded.error();
        }
        const FeatureCollection& collection = *loaded.value();
        std::optional<std::size_t> colorField;
        if (!parameters_.colorAttribute.empty()) {
            colorField = collection.field(parameters_.colorAttribute);
            if (!colorField) {
                return Error{features_->file().string() + ": no attribute '" +
                             parameters_.colorAttribute + "' (for color_attribute of source '" +
                             name() + "')"};
            }
        }
        // The window reaches out by the widest stroke so outlines of neighbours show.
        const glm::dvec2 metres = rasterizer.metresPerTexel(0.5 * w);
        const double reach = std::max({outlineWidth, lineWidth, 2.0 * parameters_.pointRadius}) /
                                 std::min(metres.x, metres.y) +
                             format.border + 1.0;
        const double dx = reach * (key.east() - key.west()) / format.size;
        const double dy = reach * (key.north() - key.south()) / format.size;
        const GeographicBounds window{key.west() - dx, key.south() - dy, key.east() + dx,
                                      key.north() + dy};
        for (const FeatureHit& hit : collection.query(window)) {
            const Feature& feature = *hit.feature;
            glm::vec3 c = parameters_.color;
            if (colorField) {
                const std::string& value = feature.attributes[*colorField];
                const std::string where = features_->file().string() + ": feature " +
                                          std::to_string(feature.id) + ": attribute '" +
                                          parameters_.colorAttribute + "'";
                if (!parameters_.colors.empty()) {
                    auto it = std::find_if(parameters_.colors.begin(), parameters_.colors.end(),
                                           [&](const auto& entry) { return entry.first == value; });
                    if (it == parameters_.colors.end()) {
                        return Error{where + ": value '" + value + "' is not in colors"};
                    }
                    c = it->second;
                } else if (std::optional<glm::vec3> parsed = parseHexColor(value)) {
                    c = *parsed;
                } else {
                    return Error{where + ": '" + value + "' is not a hex colour such as #1a8c3f"};
                }
            }
            coverage.assign(texels, 0.0f);
            switch (feature.kind) {
                case GeometryKind::Polygon:
                    if (parameters_.fill) {
                        rasterizer.fillPolygon(feature.parts, hit.longitudeShift, coverage);
                    }
                    if (outlineWidth > 0.0) {
                        strokes.assign(texels, 0.0f);
                        rasterizer.strokeLines(feature.parts, hit.longitudeShift, outlineWidth,
                                               strokes);
                        for (std::size_t i = 0; i < texels; ++i) {
                            coverage[i] = std::max(coverage[i], strokes[i]);
                        }
                    }
                    break;
                case GeometryKind::Line:
                    rasterizer.strokeLines(feature.parts, hit.longitudeShift, lineWidth, coverage);
                    break;
                case GeometryKind::Point:
                    for (const glm::dvec2& p : feature.parts.front()) {
                        rasterizer.disc(p, hit.longitudeShift, parameters_.pointRadius, coverage);
                    }
                    break;
            }
            composite(coverage, c);
        }
    } else if (key.level >= instances_->minimumLevel()) {
        const glm::dvec2 metres = rasterizer.metresPerTexel(0.5 * w);
        const double margin =
            2.0 * parameters_.pointRadius + (format.border + 1) * std::max(metres.x, metres.y);
        Result<std::vector<PlantInstance>> near = instances_->instancesNear(key, margin, provider);
        if (!near) {
            return near.error();
        }
        for (const PlantInstance& instance : near.value()) {
            const glm::vec3 c = parameters_.color * instance.tint;
            rasterizer.disc({instance.longitude, instance.latitude}, 0.0,
                            parameters_.pointRadius * instance.scale,
                            [&](std::size_t i, float coverageOfTexel) {
                                const float a =
                                    coverageOfTexel * static_cast<float>(parameters_.opacity);
                                if (parameters_.image) {
                                    colour[i] = c * a + colour[i] * (1.0f - a);
                                }
                                alpha[i] = a + alpha[i] * (1.0f - a);
                            });
        }
    }
    auto tile =
        std::make_shared<ImageTile>(key, format.size, format.border, parameters_.image ? 4 : 1);
    for (int gy = 0; gy < w; ++gy) {
        for (int gx = 0; gx < w; ++gx) {
            const std::size_t i = std::size_t(gy) * w + gx;
            const int ix = gx - format.border, iy = gy - format.border;
            if (parameters_.image) {
                const glm::vec3 straight = alpha[i] > 0.0f ? colour[i] / alpha[i] : glm::vec3(0.0f);
                for (int c = 0; c < 3; ++c) {
                    tile->at(ix, iy, c) = straight[c];
                }
                tile->at(ix, iy, 3) = alpha[i];
            } else {
                tile->at(ix, iy, 0) = alpha[i];
            }
        }
    }
    return TilePointer(std::move(tile));
}

Result<std::unique_ptr<Source>> RasterizeSource::create(const SourceBuildContext& context) {
    const BlockReader& reader = context.reader;
    Result<const Source*> features = context.input("features", false);
    if (!features) {
        return features.error();
    }
    Result<const Source*> instances = context.input("instances", false);
    if (!instances) {
        return instances.error();
    }
    if ((features.value() == nullptr) == (instances.value() == nullptr)) {
        return Error{reader.where() + "rasterize takes exactly one of 'features' and 'instances'"};
    }
    const FeatureSource* featureSource = FeatureSource::from(features.value());
    const PlantsSource* plants = PlantsSource::from(instances.value());
    if (features.value() != nullptr && featureSource == nullptr) {
        return Error{reader.where("features") + "'features' must be a features source"};
    }
    if (instances.value() != nullptr && plants == nullptr) {
        return Error{reader.where("instances") + "'instances' must be a plants source"};
    }
    RasterizeParameters p;
    if (const Value* v = reader.value("kind")) {
        if (const Word* word = v->get<Word>()) {
            p.image = word->text != "mask";
        }
    }
    p.fill = reader.boolean("fill", true);
    p.outline = reader.optionalNumber("outline").value_or(0.0);
    p.lineWidth = reader.optionalNumber("line_width").value_or(10.0);
    p.pointRadius = reader.optionalNumber("point_radius").value_or(5.0);
    p.minimumTexels = reader.optionalNumber("minimum_texels").value_or(0.0);
    p.opacity = reader.optionalNumber("opacity").value_or(1.0);
    if (std::optional<Color> c = reader.color("color")) {
        p.color = {srgbToLinear(c->r), srgbToLinear(c->g), srgbToLinear(c->b)};
    }
    p.colorAttribute = reader.string("color_attribute");
    if (const Value* colors = reader.value("colors")) {
        if (const ValueObject* object = colors->get<ValueObject>()) {
            for (const auto& [key, value] : *object) {
                const Color* c = value.get<Color>();
                if (c == nullptr) {
                    return Error{reader.where("colors") + "colors '" + key + "' must be a colour"};
                }
                p.colors.emplace_back(
                    key, glm::vec3(srgbToLinear(c->r), srgbToLinear(c->g), srgbToLinear(c->b)));
            }
        }
    }
    if (!p.colors.empty() && p.colorAttribute.empty()) {
        return Error{reader.where("colors") + "'colors' needs 'color_attribute'"};
    }
    return std::unique_ptr<Source>(
        std::make_unique<RasterizeSource>(context.block.name, featureSource, plants, std::move(p)));
}

}  // namespace sylva
