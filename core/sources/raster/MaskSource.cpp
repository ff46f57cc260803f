#include "sylva/core/sources/raster/MaskSource.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "sylva/core/base/Hash.h"
#include "sylva/core/image/ColorSpace.h"
#include "sylva/core/image/RankFilter.h"

namespace sylva {
namespace {

constexpr double kMeanRadius = 6371008.8;  // metres

// Slot of a variable: input * 4 + channel.
std::optional<int> resolveName(std::string_view name, const std::vector<const Source*>& inputs) {
    auto channelOf = [](std::string_view suffix) -> int {
        if (suffix == "r" || suffix == "b1")
            return 0;
        if (suffix == "g" || suffix == "b2")
            return 1;
        if (suffix == "b" || suffix == "b3")
            return 2;
        if (suffix == "a" || suffix == "b4")
            return 3;
        return -1;
    };
    auto check = [&](std::size_t input, int channel) -> std::optional<int> {
        if (channel < 0 || channel >= inputs[input]->channels()) {
            return std::nullopt;
        }
        return static_cast<int>(input) * 4 + channel;
    };
    if (!inputs.empty() && name.size() == 2 && name[0] == 'b' && channelOf(name) >= 0) {
        return check(0, channelOf(name));
    }
    for (std::size_t i = 0; i < inputs.size(); ++i) {
        const std::string& source = inputs[i]->name();
        if (name == source) {
            return check(i, 0);
        }
        if (name.size() > source.size() + 1 && name.substr(0, source.size()) == source &&
            name[source.size()] == '.') {
            return check(i, channelOf(name.substr(source.size() + 1)));
        }
    }
    return std::nullopt;
}

// Box blur of radius r by running sums (O(1) per texel and pass), edges clamped.
void boxBlur(std::vector<float>& grid, int width, int r) {
    if (r <= 0) {
        return;
    }
    std::vector<float> tmp(grid.size());
    for (int pass = 0; pass < 2; ++pass) {
        auto at = [&](int line, int i) -> float {
            i = std::clamp(i, 0, width - 1);
            return pass == 0 ? grid[std::size_t(line) * width + i]
                             : grid[std::size_t(i) * width + line];
        };
        for (int line = 0; line < width; ++line) {
            double sum = 0.0;
            for (int d = -r; d <= r; ++d) {
                sum += at(line, d);
            }
            for (int i = 0; i < width; ++i) {
                const float value = static_cast<float>(sum / (2 * r + 1));
                if (pass == 0) {
                    tmp[std::size_t(line) * width + i] = value;
                } else {
                    tmp[std::size_t(i) * width + line] = value;
                }
                sum += at(line, i + r + 1) - at(line, i - r);
            }
        }
        grid.swap(tmp);
    }
}

}  // namespace

MaskSource::MaskSource(std::string name, std::vector<const Source*> inputs,
                       MaskParameters parameters, BandExpression expression)
    : Source(std::move(name), "mask", PortType::Mask, 1),
      sources_(std::move(inputs)),
      parameters_(std::move(parameters)),
      expression_(std::move(expression)) {
    for (const Source* input : sources_) {
        addInput(input);
    }
    ContentHash hash;
    hash.add(parameters_.expression).add(parameters_.select);
    for (const glm::vec3& c : parameters_.classes) {
        hash.add(c.x).add(c.y).add(c.z);
    }
    hash.add(parameters_.open).add(parameters_.close).add(parameters_.feather);
    setParameterHash(hash.value());
}

Result<std::unique_ptr<MaskSource>> MaskSource::make(std::string name,
                                                     std::vector<const Source*> inputs,
                                                     MaskParameters parameters) {
    SYLVA_CHECK(!inputs.empty());
    std::string text = parameters.expression.empty() ? std::string("b1") : parameters.expression;
    Result<BandExpression> expression =
        BandExpression::parse(text, [&](std::string_view n) { return resolveName(n, inputs); });
    if (!expression) {
        return expression.error();
    }
    return std::unique_ptr<MaskSource>(new MaskSource(
        std::move(name), std::move(inputs), std::move(parameters), std::move(expression.value())));
}

int MaskSource::radiusTexels(double metres, int tileSize, int level) {
    if (metres <= 0.0) {
        return 0;
    }
    const double texelMetres =
        std::numbers::pi * kMeanRadius / (double(tileSize) * std::ldexp(1.0, level));
    return std::min(static_cast<int>(std::lround(metres / texelMetres)), tileSize);
}

Result<TilePointer> MaskSource::produce(const TileKey& key, TileProvider& provider) const {
    const TileFormat& format = provider.format();
    const int size = format.size, border = format.border;
    const int rOpen = radiusTexels(parameters_.open, size, key.level);
    const int rClose = radiusTexels(parameters_.close, size, key.level);
    const int rFeather = radiusTexels(parameters_.feather, size, key.level);
    const int pad = std::min(border + 2 * (rOpen + rClose + rFeather), size);
    const bool neighbours = pad > border;
    // Input tiles: [input][dy+1][dx+1], neighbours fetched only when needed.
    const std::size_t inputCount = sources_.size();
    std::vector<std::array<TilePointer, 9>> tiles(inputCount);
    auto fetch = [&](std::size_t input, int dx, int dy) -> Result<const ImageTile*> {
        TilePointer& slot = tiles[input][std::size_t((dy + 1) * 3 + dx + 1)];
        if (!slot) {
            TileKey k = key;
            k.x = ((key.x + dx) % key.columns() + key.columns()) % key.columns();
            k.y = std::clamp(key.y + dy, 0, key.rows() - 1);
            Result<TilePointer> t = provider.tile(*sources_[input], k);
            if (!t) {
                return t.error();
            }
            slot = t.value();
        }
        return slot.get();
    };
    const int width = size + 2 * pad;
    std::vector<float> grid(std::size_t(width) * width, 0.0f);
    std::vector<double> variables(inputCount * 4, 0.0);
    for (int gy = -pad; gy < size + pad; ++gy) {
        for (int gx = -pad; gx < size + pad; ++gx) {
            bool valid = true;
            for (std::size_t i = 0; i < inputCount; ++i) {
                int dx = 0, dy = 0, lx = gx, ly = gy;
                if (neighbours) {
                    dx = gx < 0 ? -1 : (gx >= size ? 1 : 0);
                    dy = gy < 0 ? -1 : (gy >= size ? 1 : 0);
                    // Rows beyond the poles repeat the edge row.
                    if (key.y + dy < 0 || key.y + dy >= key.rows()) {
                        dy = 0;
                        ly = std::clamp(gy, 0, size - 1);
                    } else {
                        ly = gy - dy * size;
                    }
                    lx = gx - dx * size;
                }
                Result<const ImageTile*> t = fetch(i, dx, dy);
                if (!t) {
                    return t.error();
                }
                const ImageTile& tile = *t.value();
                for (int c = 0; c < tile.channels() && c < 4; ++c) {
                    variables[i * 4 + std::size_t(c)] = tile.at(lx, ly, c);
                }
                if (sources_[i]->output() == PortType::Image && tile.channels() >= 4 &&
                    tile.at(lx, ly, 3) <= 0.0f) {
                    valid = false;
                }
            }
            float m = 0.0f;
            if (valid) {
                if (!parameters_.classes.empty()) {
                    const glm::vec3 c(variables[0], variables[1], variables[2]);
                    int best = 0;
                    float bestDistance = 1e30f;
                    for (std::size_t k = 0; k < parameters_.classes.size(); ++k) {
                        const glm::vec3 d = c - parameters_.classes[k];
                        const float distance = glm::dot(d, d);
                        if (distance < bestDistance) {
                            bestDistance = distance;
                            best = static_cast<int>(k);
                        }
                    }
                    m = best == parameters_.select ? 1.0f : 0.0f;
                } else {
                    const double v = expression_.evaluate(variables.data());
                    m = std::isfinite(v) ? static_cast<float>(std::clamp(v, 0.0, 1.0)) : 0.0f;
                }
            }
            grid[std::size_t(gy + pad) * width + (gx + pad)] = m;
        }
    }
    RankFilter::apply(grid, width, rOpen, false);
    RankFilter::apply(grid, width, rOpen, true);
    RankFilter::apply(grid, width, rClose, true);
    RankFilter::apply(grid, width, rClose, false);
    boxBlur(grid, width, rFeather);
    boxBlur(grid, width, rFeather);
    auto tile = std::make_shared<ImageTile>(key, size, border, 1);
    for (int iy = -border; iy < size + border; ++iy) {
        for (int ix = -border; ix < size + border; ++ix) {
            tile->at(ix, iy, 0) = grid[std::size_t(iy + pad) * width + (ix + pad)];
        }
    }
    return TilePointer(std::move(tile));
}

Result<std::unique_ptr<Source>> MaskSource::create(const SourceBuildContext& context) {
    const BlockReader& reader = context.reader;
    std::vector<const Source*> inputs;
    for (const char* attribute : {"input", "input2", "input3", "input4"}) {
        Result<const Source*> input = context.input(attribute, inputs.empty());
        if (!input) {
            return input.error();
        }
        if (input.value() == nullptr) {
            continue;
        }
        const PortType type = input.value()->output();
        if (type != PortType::Image && type != PortType::Mask && type != PortType::Elevation) {
            return Error{reader.where(attribute) + "'" + attribute +
                         "' must be an image, mask or elevation, but source '" +
                         input.value()->name() + "' gives " + portTypeName(type)};
        }
        inputs.push_back(input.value());
    }
    MaskParameters p;
    p.expression = reader.string("expression");
    if (const Value* classes = reader.value("classes")) {
        if (const ValueList* list = classes->get<ValueList>()) {
            for (const Value& item : *list) {
                const Color* c = item.get<Color>();
                if (c == nullptr) {
                    return Error{reader.where("classes") + "'classes' must be a list of colours"};
                }
                p.classes.emplace_back(srgbToLinear(c->r), srgbToLinear(c->g), srgbToLinear(c->b));
            }
        }
    }
    p.select = static_cast<int>(reader.optionalNumber("select").value_or(1.0)) - 1;
    if (!p.classes.empty() && (p.select < 0 || p.select >= static_cast<int>(p.classes.size()))) {
        return Error{reader.where("select") + "'select' must be a class number from 1 to " +
                     std::to_string(p.classes.size())};
    }
    if (!p.classes.empty() && inputs.front()->channels() < 3) {
        return Error{reader.where("classes") + "classification needs an image as 'input'"};
    }
    p.open = reader.optionalNumber("open").value_or(0.0);
    p.close = reader.optionalNumber("close").value_or(0.0);
    p.feather = reader.optionalNumber("feather").value_or(0.0);
    Result<std::unique_ptr<MaskSource>> made =
        make(context.block.name, std::move(inputs), std::move(p));
    if (!made) {
        return Error{reader.where("expression") + "expression: " + made.error().message};
    }
    return std::unique_ptr<Source>(std::move(made.value()));
}

}  // namespace sylva
