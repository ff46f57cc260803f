#include "sylva/core/sources/raster/HypsometricSource.h"

#include <algorithm>
#include <cmath>

#include "sylva/core/base/Hash.h"
#include "sylva/core/geo/Ellipsoid.h"
#include "sylva/core/image/ColorSpace.h"
#include "sylva/core/sources/raster/NormalMapSource.h"

namespace sylva {
namespace {

glm::vec3 fromSrgb(int r, int g, int b) {
    return {srgbToLinear(r / 255.0f), srgbToLinear(g / 255.0f), srgbToLinear(b / 255.0f)};
}

double smoothstep(double edge0, double edge1, double x) {
    if (edge1 <= edge0) {
        return x >= edge1 ? 1.0 : 0.0;
    }
    const double t = std::clamp((x - edge0) / (edge1 - edge0), 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}

}  // namespace

std::vector<HypsometricStop> HypsometricParameters::defaultRamp() {
    return {
        {0.0, fromSrgb(194, 178, 128)},     // beach sand
        {30.0, fromSrgb(86, 125, 58)},      // lowland green
        {500.0, fromSrgb(110, 135, 62)},    // hills
        {1200.0, fromSrgb(140, 124, 84)},   // dry upland
        {2200.0, fromSrgb(118, 104, 92)},   // bare mountain
        {2900.0, fromSrgb(235, 236, 240)},  // snow
    };
}

HypsometricSource::HypsometricSource(std::string name, const Source* height, const Source* normals,
                                     HypsometricParameters parameters)
    : Source(std::move(name), "hypsometric", PortType::Image, 4),
      height_(height),
      normals_(normals),
      parameters_(std::move(parameters)) {
    SYLVA_CHECK(height != nullptr && height->output() == PortType::Elevation);
    SYLVA_CHECK(normals == nullptr || normals->output() == PortType::Normals);
    if (parameters_.ramp.empty()) {
        parameters_.ramp = HypsometricParameters::defaultRamp();
    }
    addInput(height);
    if (normals != nullptr) {
        addInput(normals);
    }
    ContentHash hash;
    for (const HypsometricStop& stop : parameters_.ramp) {
        hash.add(stop.height).add(stop.color.x).add(stop.color.y).add(stop.color.z);
    }
    for (const glm::vec3& c : {parameters_.water, parameters_.shallowWater, parameters_.rock}) {
        hash.add(c.x).add(c.y).add(c.z);
    }
    hash.add(parameters_.waterDepth).add(parameters_.slopeStart).add(parameters_.slopeEnd);
    hash.add(normals != nullptr);
    setParameterHash(hash.value());
}

glm::vec3 HypsometricSource::colorAt(double height, double slope) const {
    const HypsometricParameters& p = parameters_;
    if (height < 0.0) {
        const float t = static_cast<float>(std::clamp(-height / p.waterDepth, 0.0, 1.0));
        return glm::mix(p.shallowWater, p.water, std::sqrt(t));
    }
    glm::vec3 color = p.ramp.front().color;
    for (std::size_t i = 1; i < p.ramp.size(); ++i) {
        if (height <= p.ramp[i].height) {
            const double span = p.ramp[i].height - p.ramp[i - 1].height;
            const float t = static_cast<float>(
                span > 0 ? std::clamp((height - p.ramp[i - 1].height) / span, 0.0, 1.0) : 1.0);
            color = glm::mix(p.ramp[i - 1].color, p.ramp[i].color, t);
            break;
        }
        color = p.ramp[i].color;
    }
    const float rock = static_cast<float>(smoothstep(p.slopeStart, p.slopeEnd, slope));
    return glm::mix(color, p.rock, rock);
}

glm::vec3 HypsometricSource::meanColor(double low, double high, double slope) const {
    if (!(high - low > 1e-9)) {
        return colorAt(0.5 * (low + high), slope);
    }
    // Cut [low, high] where the colour function has a kink or a step: sea level, the
    // water depth (end of the square root), every stop. Between cuts it is linear in
    // height (land) or √ of the depth (water), both integrated exactly.
    double cuts[64];
    int count = 0;
    cuts[count++] = low;
    const auto cut = [&](double height) {
        if (height > low && height < high && count < 63) {
            cuts[count++] = height;
        }
    };
    cut(-parameters_.waterDepth);
    cut(0.0);
    for (const HypsometricStop& stop : parameters_.ramp) {
        cut(stop.height);
    }
    std::sort(cuts + 1, cuts + count);
    cuts[count++] = high;
    if (count == 2 && low >= 0.0) {
        return colorAt(0.5 * (low + high), slope);  // linear piece: the mean is the middle
    }
    glm::dvec3 sum(0.0);
    const HypsometricParameters& p = parameters_;
    for (int i = 0; i + 1 < count; ++i) {
        const double a = cuts[i], b = cuts[i + 1];
        if (b <= 0.0) {
            // Water: mix(shallow, deep, √t), t = −h / depth clamped to 1; the mean of √t
            // over [tb, ta] is ⅔ (ta^1.5 − tb^1.5) / (ta − tb) (exact).
            const double ta = std::min(-a / p.waterDepth, 1.0),
                         tb = std::min(-b / p.waterDepth, 1.0);
            const double root =
                ta - tb > 1e-12 ? 2.0 / 3.0 * (std::pow(ta, 1.5) - std::pow(tb, 1.5)) / (ta - tb)
                                : std::sqrt(ta);
            sum += (b - a) * glm::mix(glm::dvec3(p.shallowWater), glm::dvec3(p.water), root);
            continue;
        }
        // Land: linear in height between cuts, so the mean is the middle's colour.
        sum += (b - a) * glm::dvec3(colorAt(0.5 * (a + b), slope));
    }
    return glm::vec3(sum / (high - low));
}

Result<TilePointer> HypsometricSource::produce(const TileKey& key, TileProvider& provider) const {
    Result<TilePointer> height = provider.tile(*height_, key);
    if (!height) {
        return height.error();
    }
    TilePointer normals;
    if (normals_ != nullptr) {
        Result<TilePointer> n = provider.tile(*normals_, key);
        if (!n) {
            return n.error();
        }
        normals = n.value();
    }
    const ImageTile& h = *height.value();
    const TileFormat& format = provider.format();
    auto tile = std::make_shared<ImageTile>(key, format.size, format.border, 4);
    for (int iy = -format.border; iy < format.size + format.border; ++iy) {
        const double latitude = tile->texelLatitude(iy);
        for (int ix = -format.border; ix < format.size + format.border; ++ix) {
            const glm::dvec3 up = Ellipsoid::surfaceNormal(latitude, tile->texelLongitude(ix));
            glm::dvec3 normal;
            if (normals) {
                normal = glm::dvec3(normals->at(ix, iy, 0), normals->at(ix, iy, 1),
                                    normals->at(ix, iy, 2));
            } else {
                normal = NormalMapSource::normalAt(h, ix, iy, 1.0);
            }
            const double slope =
                std::acos(std::clamp(glm::dot(glm::normalize(normal), up), -1.0, 1.0));
            const double elevation = h.at(ix, iy, 0);
            // The texel's colour is the mean colour of the heights it spans, not the colour
            // of its centre height: the ramp is a nonlinear function of a band-limited
            // height, and point-sampling it made every coarse texel whose centre lies in a
            // thin band (the 0-30 m beach) wholly that colour — from space a staircase of
            // sand texels along the coast and sand rectangles on lowlands (issue 16). With
            // the height changing linearly across the texel (central differences), the
            // texel's heights are uniform over [h - change / 2, h + change / 2].
            const int x0 = std::max(ix - 1, -format.border),
                      x1 = std::min(ix + 1, format.size + format.border - 1);
            const int y0 = std::max(iy - 1, -format.border),
                      y1 = std::min(iy + 1, format.size + format.border - 1);
            const double change = std::hypot((h.at(x1, iy, 0) - h.at(x0, iy, 0)) / (x1 - x0),
                                             (h.at(ix, y1, 0) - h.at(ix, y0, 0)) / (y1 - y0));
            const glm::vec3 c =
                meanColor(elevation - 0.5 * change, elevation + 0.5 * change, slope);
            tile->at(ix, iy, 0) = c.x;
            tile->at(ix, iy, 1) = c.y;
            tile->at(ix, iy, 2) = c.z;
            tile->at(ix, iy, 3) = 1.0f;
        }
    }
    return TilePointer(std::move(tile));
}

namespace {
glm::vec3 linear(const Color& c) {
    return {srgbToLinear(c.r), srgbToLinear(c.g), srgbToLinear(c.b)};
}
}  // namespace

Result<std::unique_ptr<Source>> HypsometricSource::create(const SourceBuildContext& context) {
    const Block& block = context.block;
    const BlockReader& reader = context.reader;
    Result<const Source*> height = context.input("height", true);
    if (!height) {
        return height.error();
    }
    Result<const Source*> normals = context.input("normals", false);
    if (!normals) {
        return normals.error();
    }
    HypsometricParameters p;
    p.water = linear(*reader.color("water"));
    p.shallowWater = linear(*reader.color("shallow_water"));
    p.rock = linear(*reader.color("rock"));
    for (auto [name, target] : {std::pair{"water_depth", &p.waterDepth},
                                {"slope_start", &p.slopeStart},
                                {"slope_end", &p.slopeEnd}}) {
        Result<double> v = reader.number(name);
        if (!v) {
            return v.error();
        }
        *target = v.value();
    }
    if (const Value* ramp = reader.value("ramp")) {
        const ValueList* stops = ramp->get<ValueList>();
        if (stops == nullptr || stops->empty()) {
            return Error{reader.where("ramp") + "'ramp' must be a non-empty list of stops"};
        }
        for (const Value& stop : *stops) {
            const ValueObject* object = stop.get<ValueObject>();
            const Quantity* stopHeight = nullptr;
            const Color* stopColor = nullptr;
            if (object != nullptr) {
                for (const auto& [key, value] : *object) {
                    if (key == "height") {
                        stopHeight = value.get<Quantity>();
                    } else if (key == "color") {
                        stopColor = value.get<Color>();
                    }
                }
            }
            if (stopHeight == nullptr || stopColor == nullptr ||
                (stopHeight->dimension != Dimension::Length &&
                 stopHeight->dimension != Dimension::None)) {
                return Error{stop.location.toString() + ": source '" + block.name +
                             "': a ramp stop must be { height = <length>, color = <colour> }"};
            }
            if (!p.ramp.empty() && stopHeight->value < p.ramp.back().height) {
                return Error{stop.location.toString() + ": source '" + block.name +
                             "': ramp stops must be in ascending height"};
            }
            p.ramp.push_back({stopHeight->value, linear(*stopColor)});
        }
    }
    return std::unique_ptr<Source>(std::make_unique<HypsometricSource>(
        block.name, height.value(), normals.value(), std::move(p)));
}

}  // namespace sylva
