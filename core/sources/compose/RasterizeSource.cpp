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

namespace {

// Premultiplied accumulation over the tile's texels (border included): colour × alpha
// and alpha, composited "over" in drawing order.
class Canvas {
public:
    Canvas(int width, bool image, double opacity)
        : texels_(std::size_t(width) * width),
          image_(image),
          opacity_(static_cast<float>(opacity)),
          colour_(image ? texels_ : 0, glm::vec3(0.0f)),
          alpha_(texels_, 0.0f) {}

    std::size_t texels() const { return texels_; }

    void add(std::size_t i, float coverage, const glm::vec3& c) {
        const float a = coverage * opacity_;
        if (image_) {
            colour_[i] = c * a + colour_[i] * (1.0f - a);
        }
        alpha_[i] = a + alpha_[i] * (1.0f - a);
    }
    void composite(const std::vector<float>& coverage, const glm::vec3& c) {
        for (std::size_t i = 0; i < texels_; ++i) {
            if (coverage[i] * opacity_ <= 0.0f) {
                continue;
            }
            add(i, coverage[i], c);
        }
    }

    // Straight colour + alpha (image) or the alpha alone (mask).
    TilePointer tile(const TileKey& key, const TileFormat& format, int width) const {
        auto tile = std::make_shared<ImageTile>(key, format.size, format.border, image_ ? 4 : 1);
        for (int gy = 0; gy < width; ++gy) {
            for (int gx = 0; gx < width; ++gx) {
                const std::size_t i = std::size_t(gy) * width + gx;
                const int ix = gx - format.border, iy = gy - format.border;
                if (image_) {
                    const glm::vec3 straight =
                        alpha_[i] > 0.0f ? colour_[i] / alpha_[i] : glm::vec3(0.0f);
                    for (int c = 0; c < 3; ++c) {
                        tile->at(ix, iy, c) = straight[c];
                    }
                    tile->at(ix, iy, 3) = alpha_[i];
                } else {
                    tile->at(ix, iy, 0) = alpha_[i];
                }
            }
        }
        return tile;
    }

private:
    std::size_t texels_;
    bool image_;
    float opacity_;
    std::vector<glm::vec3> colour_;
    std::vector<float> alpha_;
};

// A feature's colour: `color`, or from the colour attribute (through `colors`, or as a
// hex string).
Result<glm::vec3> featureColour(const RasterizeParameters& parameters, const Feature& feature,
                                std::optional<std::size_t> colorField, const std::string& file) {
    if (!colorField) {
        return parameters.color;
    }
    const std::string& value = feature.attributes[*colorField];
    const std::string where = file + ": feature " + std::to_string(feature.id) + ": attribute '" +
                              parameters.colorAttribute + "'";
    if (!parameters.colors.empty()) {
        auto it = std::find_if(parameters.colors.begin(), parameters.colors.end(),
                               [&](const auto& entry) { return entry.first == value; });
        if (it == parameters.colors.end()) {
            return Error{where + ": value '" + value + "' is not in colors"};
        }
        return it->second;
    }
    if (std::optional<glm::vec3> parsed = RasterizeSource::parseHexColor(value)) {
        return *parsed;
    }
    return Error{where + ": '" + value + "' is not a hex colour such as #1a8c3f"};
}

// The stroke widths in metres, at least `minimum_texels` wide at the tile's centre row, and
// the opacity that keeps a widened stroke's ink at its metric area: a 150 m border drawn
// 1.5 texels (1.8 km) wide on a 1.2 km-texel tile covers its texels at 150 / 1800, so
// coverage summed over a coarse tile is still the line's length × 150 m and the line fades
// with distance instead of flooding the coarse levels.
struct StrokeWidths {
    double outline = 0.0;
    double line = 0.0;
    float outlineOpacity = 1.0f;  // metric width / drawn width, in (0, 1]
    float lineOpacity = 1.0f;
};

StrokeWidths strokeWidths(const RasterizeParameters& parameters,
                          const CoverageRasterizer& rasterizer) {
    const double minimumWidth =
        parameters.minimumTexels * rasterizer.metresPerTexel(0.5 * rasterizer.width()).y;
    StrokeWidths widths;
    widths.outline = parameters.outline > 0.0 ? std::max(parameters.outline, minimumWidth) : 0.0;
    widths.line = parameters.lineWidth > 0.0 ? std::max(parameters.lineWidth, minimumWidth) : 0.0;
    if (widths.outline > 0.0) {
        widths.outlineOpacity = float(parameters.outline / widths.outline);
    }
    if (widths.line > 0.0) {
        widths.lineOpacity = float(parameters.lineWidth / widths.line);
    }
    return widths;
}

// One feature's coverage: filled and/or outlined polygons, stroked lines, point discs.
void featureCoverage(const RasterizeParameters& parameters, const CoverageRasterizer& rasterizer,
                     const FeatureHit& hit, const StrokeWidths& widths,
                     std::vector<float>& coverage, std::vector<float>& strokes) {
    const Feature& feature = *hit.feature;
    const std::size_t texels = coverage.size();
    switch (feature.kind) {
        case GeometryKind::Polygon:
            if (parameters.fill) {
                rasterizer.fillPolygon(feature.parts, hit.longitudeShift, coverage);
            }
            if (widths.outline > 0.0) {
                strokes.assign(texels, 0.0f);
                rasterizer.strokeLines(feature.parts, hit.longitudeShift, widths.outline, strokes);
                for (std::size_t i = 0; i < texels; ++i) {
                    coverage[i] = std::max(coverage[i], strokes[i] * widths.outlineOpacity);
                }
            }
            break;
        case GeometryKind::Line:
            rasterizer.strokeLines(feature.parts, hit.longitudeShift, widths.line, coverage);
            if (widths.lineOpacity < 1.0f) {
                for (float& c : coverage) {
                    c *= widths.lineOpacity;
                }
            }
            break;
        case GeometryKind::Point:
            for (const glm::dvec2& p : feature.parts.front()) {
                rasterizer.disc(p, hit.longitudeShift, parameters.pointRadius, coverage);
            }
            break;
    }
}

// Every feature near the tile, in file order. The window reaches out by the widest
// stroke so outlines of neighbours show.
Status drawFeatures(const RasterizeParameters& parameters, const FeatureSource& features,
                    const std::string& sourceName, const TileKey& key, const TileFormat& format,
                    const CoverageRasterizer& rasterizer, Canvas& canvas) {
    Result<std::shared_ptr<const FeatureCollection>> loaded = features.collection();
    if (!loaded) {
        return loaded.error();
    }
    const FeatureCollection& collection = *loaded.value();
    const std::string file = features.file().string();
    std::optional<std::size_t> colorField;
    if (!parameters.colorAttribute.empty()) {
        colorField = collection.field(parameters.colorAttribute);
        if (!colorField) {
            return Error{file + ": no attribute '" + parameters.colorAttribute +
                         "' (for color_attribute of source '" + sourceName + "')"};
        }
    }
    const StrokeWidths widths = strokeWidths(parameters, rasterizer);
    const glm::dvec2 metres = rasterizer.metresPerTexel(0.5 * rasterizer.width());
    const double reach = std::max({widths.outline, widths.line, 2.0 * parameters.pointRadius}) /
                             std::min(metres.x, metres.y) +
                         format.border + 1.0;
    const double dx = reach * (key.east() - key.west()) / format.size;
    const double dy = reach * (key.north() - key.south()) / format.size;
    const GeographicBounds window{key.west() - dx, key.south() - dy, key.east() + dx,
                                  key.north() + dy};
    std::vector<float> coverage, strokes;
    for (const FeatureHit& hit : collection.query(window)) {
        Result<glm::vec3> c = featureColour(parameters, *hit.feature, colorField, file);
        if (!c) {
            return c.error();
        }
        coverage.assign(canvas.texels(), 0.0f);
        featureCoverage(parameters, rasterizer, hit, widths, coverage, strokes);
        canvas.composite(coverage, *c);
    }
    return Status::success();
}

// Instances near the tile as discs of point_radius × scale, colour × tint.
Status drawInstances(const RasterizeParameters& parameters, const PlantsSource& instances,
                     const TileKey& key, const TileFormat& format,
                     const CoverageRasterizer& rasterizer, TileProvider& provider, Canvas& canvas) {
    const glm::dvec2 metres = rasterizer.metresPerTexel(0.5 * rasterizer.width());
    const double margin =
        2.0 * parameters.pointRadius + (format.border + 1) * std::max(metres.x, metres.y);
    Result<std::vector<PlantInstance>> near = instances.instancesNear(key, margin, provider);
    if (!near) {
        return near.error();
    }
    for (const PlantInstance& instance : near.value()) {
        const glm::vec3 c = parameters.color * instance.tint;
        rasterizer.disc(
            {instance.longitude, instance.latitude}, 0.0, parameters.pointRadius * instance.scale,
            [&](std::size_t i, float coverageOfTexel) { canvas.add(i, coverageOfTexel, c); });
    }
    return Status::success();
}

}  // namespace

Result<TilePointer> RasterizeSource::produce(const TileKey& key, TileProvider& provider) const {
    const TileFormat& format = provider.format();
    const CoverageRasterizer rasterizer(key, format.size, format.border);
    Canvas canvas(rasterizer.width(), parameters_.image, parameters_.opacity);
    if (features_ != nullptr) {
        if (Status drawn =
                drawFeatures(parameters_, *features_, name(), key, format, rasterizer, canvas);
            !drawn) {
            return drawn.error();
        }
    } else if (key.level >= instances_->minimumLevel()) {
        if (Status drawn =
                drawInstances(parameters_, *instances_, key, format, rasterizer, provider, canvas);
            !drawn) {
            return drawn.error();
        }
    }
    return canvas.tile(key, format, rasterizer.width());
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
