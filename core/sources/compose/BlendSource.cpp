#include "sylva/core/sources/compose/BlendSource.h"

#include <algorithm>
#include <cmath>
#include <numbers>

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

}  // namespace

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
    Result<TilePointer> baseTile = provider.tile(*base_, key);
    if (!baseTile) {
        return baseTile.error();
    }
    Result<TilePointer> overTile = provider.tile(*over_, key);
    if (!overTile) {
        return overTile.error();
    }
    TilePointer maskTile, coverageTile, coarseTile;
    if (mask_ != nullptr) {
        Result<TilePointer> m = provider.tile(*mask_, key);
        if (!m) {
            return m.error();
        }
        maskTile = m.value();
    }
    const bool image = output() == PortType::Image;
    const int coverageChannel = image ? 3 : 0;
    if (overCoverage_ != nullptr) {
        if (overCoverage_ == over_) {
            coverageTile = overTile.value();
        } else {
            Result<TilePointer> c = provider.tile(*overCoverage_, key);
            if (!c) {
                return c.error();
            }
            coverageTile = c.value();
        }
        if (parameters_.feather > 0.0) {
            const int level = featherLevel(parameters_.feather, provider.format().size, key.level);
            Result<TilePointer> c = provider.tile(*overCoverage_, coarseKey(key, level));
            if (!c) {
                return c.error();
            }
            coarseTile = c.value();
        }
    }
    const ImageTile& base = *baseTile.value();
    const ImageTile& over = *overTile.value();
    auto tile = std::make_shared<ImageTile>(base);
    const int border = tile->border(), size = tile->size();
    for (int iy = -border; iy < size + border; ++iy) {
        const double latitude = tile->texelLatitude(iy);
        for (int ix = -border; ix < size + border; ++ix) {
            double w = parameters_.opacity;
            if (maskTile) {
                w *= std::clamp<double>(maskTile->at(ix, iy, 0), 0.0, 1.0);
            }
            if (coverageTile) {
                w *= std::clamp<double>(coverageTile->at(ix, iy, coverageChannel), 0.0, 1.0);
            }
            if (coarseTile && w > 0.0) {
                w *= smoothstep(
                    0.5, 1.0,
                    sample(*coarseTile, coverageChannel, tile->texelLongitude(ix), latitude));
            }
            if (w <= 0.0) {
                continue;
            }
            if (image) {
                for (int c = 0; c < 3; ++c) {
                    const double b = base.at(ix, iy, c), o = over.at(ix, iy, c);
                    double f = o;
                    switch (parameters_.mode) {
                        case BlendMode::Normal:
                            f = o;
                            break;
                        case BlendMode::Multiply:
                            f = b * o;
                            break;
                        case BlendMode::Screen:
                            f = 1.0 - (1.0 - b) * (1.0 - o);
                            break;
                        case BlendMode::Add:
                            f = b + o;
                            break;
                        case BlendMode::Min:
                            f = std::min(b, o);
                            break;
                        case BlendMode::Max:
                            f = std::max(b, o);
                            break;
                    }
                    tile->at(ix, iy, c) = static_cast<float>(b + (f - b) * w);
                }
                if (tile->channels() > 3) {
                    const double a = base.at(ix, iy, 3);
                    tile->at(ix, iy, 3) = static_cast<float>(w + a * (1.0 - w));
                }
            } else {
                const double b = base.at(ix, iy, 0), o = over.at(ix, iy, 0);
                double h = b;
                switch (parameters_.mode) {
                    case BlendMode::Add:
                        h = b + w * o;
                        break;
                    case BlendMode::Min:
                        h = b + (std::min(b, o) - b) * w;
                        break;
                    case BlendMode::Max:
                        h = b + (std::max(b, o) - b) * w;
                        break;
                    default:
                        h = b + (o - b) * w;
                        break;
                }
                tile->at(ix, iy, 0) = static_cast<float>(h);
            }
        }
    }
    return TilePointer(std::move(tile));
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
