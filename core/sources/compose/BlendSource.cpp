#include "sylva/core/sources/compose/BlendSource.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <tuple>
#include <vector>

#include "sylva/core/base/Hash.h"
#include "sylva/core/sources/raster/RasterSource.h"
#include "sylva/core/sources/vector/ElevationEditSource.h"

namespace sylva {
namespace {

constexpr double kMeanRadius = 6371008.8;  // metres (IUGG mean Earth radius)

double smoothstep(double edge0, double edge1, double x) {
    const double t = std::clamp((x - edge0) / (edge1 - edge0), 0.0, 1.0);
    return t * t * (3.0 - 2.0 * t);
}

// The tile of (level, lonReduction clamped) containing the centre of `key`.
TileKey coarseKey(const TileKey& key, int level) {
    TileKey coarse;
    coarse.level = level;
    coarse.lonReduction = std::min(key.lonReduction, level + 1);
    const double lon = 0.5 * (key.west() + key.east());
    const double lat = 0.5 * (key.north() + key.south());
    const int columns = coarse.columns(), rows = coarse.rows();
    coarse.x = std::clamp(
        static_cast<int>(std::floor((lon + std::numbers::pi) / (2 * std::numbers::pi) * columns)),
        0, columns - 1);
    coarse.y = std::clamp(
        static_cast<int>(std::floor((std::numbers::pi / 2 - lat) / std::numbers::pi * rows)), 0,
        rows - 1);
    return coarse;
}

// Bilinear sample of `channel` of `tile` at a longitude/latitude (radians).
double sample(const ImageTile& tile, int channel, double longitude, double latitude) {
    const double low = -tile.border(), high = tile.size() + tile.border() - 1;
    const double u =
        std::clamp((longitude - tile.key().west()) / tile.texelWidth() - 0.5, low, high);
    const double v =
        std::clamp((tile.key().north() - latitude) / tile.texelHeight() - 0.5, low, high);
    const int i0 = std::min(static_cast<int>(std::floor(u)), static_cast<int>(high) - 1);
    const int j0 = std::min(static_cast<int>(std::floor(v)), static_cast<int>(high) - 1);
    const double fu = u - i0, fv = v - j0;
    return (1 - fv) * ((1 - fu) * tile.at(i0, j0, channel) + fu * tile.at(i0 + 1, j0, channel)) +
           fv * ((1 - fu) * tile.at(i0, j0 + 1, channel) + fu * tile.at(i0 + 1, j0 + 1, channel));
}

// An image channel: the blend of base b and over o by the mode (before the weight).
double blendChannel(BlendMode mode, double b, double o) {
    switch (mode) {
        case BlendMode::Normal:
            return o;
        case BlendMode::Multiply:
            return b * o;
        case BlendMode::Screen:
            return 1.0 - (1.0 - b) * (1.0 - o);
        case BlendMode::Add:
            return b + o;
        case BlendMode::Min:
            return std::min(b, o);
        case BlendMode::Max:
            return std::max(b, o);
    }
    return o;
}

// An elevation: replace (any other mode), add, min or max with weight w.
double blendHeight(BlendMode mode, double b, double o, double w) {
    switch (mode) {
        case BlendMode::Add:
            return b + w * o;
        case BlendMode::Min:
            return b + (std::min(b, o) - b) * w;
        case BlendMode::Max:
            return b + (std::max(b, o) - b) * w;
        default:
            return b + (o - b) * w;
    }
}

// A weight this close to 1 is 1: bilinear sums of full coverage land within a few ulps of
// 1, and a texel blended with such a weight is the over-source's value to float precision.
// Snapping makes it exactly that, so a tile whose texels all take the over-source (read
// alone, below) equals the same texels blended one by one.
constexpr double kWholeWeight = 1.0 - 1e-9;

double wholeOrClamped(double weight) {
    return weight >= kWholeWeight ? 1.0 : std::max(weight, 0.0);
}

}  // namespace

// The input tiles of one produce: the mask, the over-source's coverage and its coarse
// (feather) tile when they apply, and base and over when the weights need them.
struct BlendSource::Inputs {
    TilePointer base, over, mask, coverage, coarse;
};

BlendSource::BlendSource(std::string name, const Source* base, const Source* over,
                         const Source* mask, const BlendParameters& parameters)
    : Source(std::move(name), "blend", base->output(), base->channels()),
      base_(base),
      over_(over),
      mask_(mask),
      overCoverage_(nullptr),
      parameters_(parameters) {
    SYLVA_CHECK(base->output() == over->output());
    SYLVA_CHECK(base->output() == PortType::Elevation || base->output() == PortType::Image);
    SYLVA_CHECK(mask == nullptr || mask->output() == PortType::Mask);
    addInput(base);
    addInput(over);
    if (mask != nullptr) {
        addInput(mask);
    }
    overCoverage_ = output() == PortType::Image ? over : coverageOf(*over);
    setParameterHash(ContentHash()
                         .add(static_cast<int>(parameters_.mode))
                         .add(parameters_.opacity)
                         .add(parameters_.feather)
                         .add(mask != nullptr)
                         .value());
}

const Source* BlendSource::coverageOf(const Source& elevation) {
    if (const auto* raster = dynamic_cast<const RasterSource*>(&elevation)) {
        return raster->coverage();
    }
    if (const auto* blend = dynamic_cast<const BlendSource*>(&elevation)) {
        return blend->output() == PortType::Elevation ? coverageOf(*blend->base_) : nullptr;
    }
    if (const auto* edit = dynamic_cast<const ElevationEditSource*>(&elevation)) {
        return coverageOf(edit->input());  // edits reshape heights, not where data exists
    }
    return nullptr;
}

int BlendSource::featherLevel(double featherMetres, int tileSize, int level) {
    if (featherMetres <= 0.0) {
        return level;
    }
    // Texels of about twice the feather: the coverage then climbs from 0.5 at the edge to
    // 1 over about one feather (box read + two bilinear interpolations, measured).
    const double texelsPerFeather =
        std::numbers::pi * kMeanRadius / (tileSize * 2.0 * featherMetres);
    const int wanted = static_cast<int>(std::ceil(std::log2(std::max(texelsPerFeather, 1.0))));
    return std::clamp(wanted, 0, level);
}

Result<TilePointer> BlendSource::produce(const TileKey& key, TileProvider& provider) const {
    // Lazy in both inputs (seed 001's demand-driven tile evaluation carried into a blend):
    // the weights come first, from the mask and the over-source's coverage, and an input
    // whose texels all have weight 0 (over) or 1 (base under a replacing over) is never
    // asked for. Inside a DEM the procedural relief under it is then never synthesised.
    Inputs in;
    if (std::optional<Error> error = fetchWeightInputs(key, provider, in)) {
        return *error;
    }
    const TexelWeights weights = texelWeights(in, key, provider.format());
    const bool anyOver = weights.highest > 0;
    const bool replacesAll = parameters_.mode == BlendMode::Normal && weights.lowest >= 1.0;
    for (auto [source, slot, needed] :
         {std::tuple{base_, &in.base, !replacesAll}, std::tuple{over_, &in.over, anyOver}}) {
        if (!needed || *slot) {
            continue;
        }
        Result<TilePointer> tile = provider.tile(*source, key);
        if (!tile) {
            return tile.error();
        }
        *slot = tile.value();
    }
    if (replacesAll) {
        return TilePointer(std::make_shared<ImageTile>(*in.over));
    }
    auto tile = std::make_shared<ImageTile>(*in.base);
    if (anyOver) {
        blendTexels(*in.over, weights, *tile);
    }
    return TilePointer(std::move(tile));
}

std::optional<Error> BlendSource::fetchWeightInputs(const TileKey& key, TileProvider& provider,
                                                    Inputs& in) const {
    if (mask_ != nullptr) {
        Result<TilePointer> m = provider.tile(*mask_, key);
        if (!m) {
            return m.error();
        }
        in.mask = m.value();
    }
    if (overCoverage_ == nullptr) {
        return std::nullopt;
    }
    Result<TilePointer> c = provider.tile(*overCoverage_, key);
    if (!c) {
        return c.error();
    }
    in.coverage = c.value();
    if (overCoverage_ == over_) {
        in.over = in.coverage;  // an image's coverage is its own alpha
    }
    if (parameters_.feather > 0.0) {
        const int level = featherLevel(parameters_.feather, provider.format().size, key.level);
        Result<TilePointer> coarse = provider.tile(*overCoverage_, coarseKey(key, level));
        if (!coarse) {
            return coarse.error();
        }
        in.coarse = coarse.value();
    }
    return std::nullopt;
}

BlendSource::TexelWeights BlendSource::texelWeights(const Inputs& in, const TileKey& key,
                                                    const TileFormat& format) const {
    if (!in.coverage && !in.mask) {
        const double opacity = wholeOrClamped(parameters_.opacity);
        return {{}, opacity, opacity};  // the opacity alone
    }
    const int border = format.border, side = format.size + 2 * border;
    std::vector<double> weights(std::size_t(side) * side);
    // The texel grid of the output tile (every input shares the key's grid).
    const ImageTile& grid = in.coverage ? *in.coverage : *in.mask;
    SYLVA_CHECK(grid.key() == key && grid.size() == format.size && grid.border() == border);
    const int coverageChannel = output() == PortType::Image ? 3 : 0;
    for (int iy = -border; iy < grid.size() + border; ++iy) {
        const double latitude = grid.texelLatitude(iy);
        for (int ix = -border; ix < grid.size() + border; ++ix) {
            double w = parameters_.opacity;
            if (in.mask) {
                w *= std::clamp<double>(in.mask->at(ix, iy, 0), 0.0, 1.0);
            }
            if (in.coverage) {
                w *= std::clamp<double>(in.coverage->at(ix, iy, coverageChannel), 0.0, 1.0);
            }
            if (in.coarse && w > 0.0) {
                w *= smoothstep(
                    0.5, 1.0,
                    sample(*in.coarse, coverageChannel, grid.texelLongitude(ix), latitude));
            }
            weights[std::size_t(iy + border) * side + (ix + border)] = wholeOrClamped(w);
        }
    }
    const auto [lowest, highest] = std::ranges::minmax(weights);
    return {std::move(weights), lowest, highest};
}

void BlendSource::blendTexels(const ImageTile& over, const TexelWeights& weights,
                              ImageTile& tile) const {
    const int border = tile.border(), size = tile.size(), side = size + 2 * border;
    for (int iy = -border; iy < size + border; ++iy) {
        for (int ix = -border; ix < size + border; ++ix) {
            const double w = weights.at(std::size_t(iy + border) * side + (ix + border));
            if (w <= 0.0) {
                continue;
            }
            if (output() != PortType::Image) {
                tile.at(ix, iy, 0) = static_cast<float>(
                    blendHeight(parameters_.mode, tile.at(ix, iy, 0), over.at(ix, iy, 0), w));
                continue;
            }
            for (int c = 0; c < 3; ++c) {
                const double b = tile.at(ix, iy, c);
                const double f = blendChannel(parameters_.mode, b, over.at(ix, iy, c));
                tile.at(ix, iy, c) = static_cast<float>(b + (f - b) * w);
            }
            if (tile.channels() > 3) {
                const double a = tile.at(ix, iy, 3);
                tile.at(ix, iy, 3) = static_cast<float>(w + a * (1.0 - w));
            }
        }
    }
}

Result<std::unique_ptr<Source>> BlendSource::create(const SourceBuildContext& context) {
    const BlockReader& reader = context.reader;
    Result<const Source*> base = context.input("base", true);
    if (!base) {
        return base.error();
    }
    Result<const Source*> over = context.input("over", true);
    if (!over) {
        return over.error();
    }
    Result<const Source*> mask = context.input("mask", false);
    if (!mask) {
        return mask.error();
    }
    const PortType type = base.value()->output();
    if (type != PortType::Elevation && type != PortType::Image) {
        return Error{reader.where("base") +
                     "'base' must be an elevation or an image, but source '" +
                     base.value()->name() + "' gives " + portTypeName(type)};
    }
    if (over.value()->output() != type || over.value()->channels() != base.value()->channels()) {
        return Error{reader.where("over") + "'over' must give " + portTypeName(type) +
                     " like 'base', but source '" + over.value()->name() + "' gives " +
                     portTypeName(over.value()->output())};
    }
    BlendParameters p;
    p.opacity = reader.optionalNumber("opacity").value_or(1.0);
    p.feather = reader.optionalNumber("feather").value_or(0.0);
    std::string mode = "normal";
    if (const Value* v = reader.value("mode")) {
        if (const Word* w = v->get<Word>()) {
            mode = w->text;
        }
    }
    if (mode == "multiply") {
        p.mode = BlendMode::Multiply;
    } else if (mode == "screen") {
        p.mode = BlendMode::Screen;
    } else if (mode == "add") {
        p.mode = BlendMode::Add;
    } else if (mode == "min") {
        p.mode = BlendMode::Min;
    } else if (mode == "max") {
        p.mode = BlendMode::Max;
    }
    if (type == PortType::Elevation &&
        (p.mode == BlendMode::Multiply || p.mode == BlendMode::Screen)) {
        return Error{reader.where("mode") + "mode '" + mode +
                     "' is for images; elevation blends use replace, add, min or max"};
    }
    return std::unique_ptr<Source>(std::make_unique<BlendSource>(context.block.name, base.value(),
                                                                 over.value(), mask.value(), p));
}

}  // namespace sylva
