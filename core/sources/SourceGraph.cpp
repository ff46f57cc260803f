#include "sylva/core/sources/SourceGraph.h"

#include <functional>
#include <map>
#include <set>

#include "sylva/core/image/ColorSpace.h"
#include "sylva/core/scene/BlockReader.h"
#include "sylva/core/sources/HypsometricSource.h"
#include "sylva/core/sources/NoiseSource.h"
#include "sylva/core/sources/NormalMapSource.h"

namespace sylva {
namespace {

glm::vec3 linear(const Color& c) {
    return {srgbToLinear(c.r), srgbToLinear(c.g), srgbToLinear(c.b)};
}

using Resolve = std::function<Result<const Source*>(const BlockReader&, std::string_view, bool)>;

Result<std::unique_ptr<Source>> createNoise(const Block& block, const BlockReader& reader) {
    NoiseParameters p;
    for (auto [name, target] : {std::pair{"amplitude", &p.amplitude},
                                {"base_wavelength", &p.baseWavelength},
                                {"lacunarity", &p.lacunarity},
                                {"gain", &p.gain},
                                {"ridges", &p.ridges},
                                {"ridge_wavelength", &p.ridgeWavelength},
                                {"roughness", &p.roughness},
                                {"offset", &p.offset}}) {
        Result<double> v = reader.number(name);
        if (!v) {
            return v.error();
        }
        *target = v.value();
    }
    Result<double> seed = reader.number("seed");
    Result<double> octaves = reader.number("octaves");
    if (!seed) {
        return seed.error();
    }
    if (!octaves) {
        return octaves.error();
    }
    p.seed = static_cast<std::uint32_t>(seed.value());
    p.octaves = static_cast<int>(octaves.value());
    return std::unique_ptr<Source>(std::make_unique<NoiseSource>(block.name, p));
}

Result<std::unique_ptr<Source>> createNormalMap(const Block& block, const BlockReader& reader,
                                                const Resolve& resolve) {
    Result<const Source*> height = resolve(reader, "height", true);
    if (!height) {
        return height.error();
    }
    Result<double> exaggeration = reader.number("exaggeration");
    if (!exaggeration) {
        return exaggeration.error();
    }
    return std::unique_ptr<Source>(
        std::make_unique<NormalMapSource>(block.name, height.value(), exaggeration.value()));
}

Result<std::unique_ptr<Source>> createHypsometric(const Block& block, const BlockReader& reader,
                                                  const Resolve& resolve) {
    Result<const Source*> height = resolve(reader, "height", true);
    if (!height) {
        return height.error();
    }
    Result<const Source*> normals = resolve(reader, "normals", false);
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
                (stopHeight->dimension != Dimension::Length && stopHeight->dimension != Dimension::None)) {
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
    return std::unique_ptr<Source>(
        std::make_unique<HypsometricSource>(block.name, height.value(), normals.value(), std::move(p)));
}

}  // namespace

SourceGraph::SourceGraph(SourceGraph&&) noexcept = default;
SourceGraph& SourceGraph::operator=(SourceGraph&&) noexcept = default;
SourceGraph::~SourceGraph() = default;

const Source* SourceGraph::find(std::string_view name) const {
    for (const auto& source : sources_) {
        if (source->name() == name) {
            return source.get();
        }
    }
    return nullptr;
}

Result<SourceGraph> SourceGraph::build(const ProjectModel& model) {
    const SchemaRegistry& schema = SchemaRegistry::builtin();
    SourceGraph graph;
    std::map<std::string, const Block*, std::less<>> blocks;
    for (const Block& block : model.sources) {
        blocks.emplace(block.name, &block);
    }
    std::set<std::string, std::less<>> visiting;
    std::function<Result<const Source*>(const Block&)> create;

    Resolve resolve = [&](const BlockReader& reader, std::string_view attribute,
                          bool required) -> Result<const Source*> {
        std::optional<std::string> target = reader.reference(attribute);
        if (!target) {
            if (required) {
                return Error{reader.where(attribute) + "missing input '" + std::string(attribute) + "'"};
            }
            return static_cast<const Source*>(nullptr);
        }
        auto it = blocks.find(*target);
        if (it == blocks.end()) {
            return Error{reader.where(attribute) + "unknown source '" + *target + "'"};
        }
        if (visiting.count(*target) != 0) {
            return Error{reader.where(attribute) + "dependency cycle through source '" + *target + "'"};
        }
        Result<const Source*> input = create(*it->second);
        if (!input) {
            return input;
        }
        const KindSchema* kind = schema.find("source", reader.block().kind);
        const AttributeSchema* port = kind ? kind->find(attribute) : nullptr;
        if (port != nullptr && port->port != PortType::None && input.value()->output() != port->port) {
            return Error{reader.where(attribute) + "'" + std::string(attribute) + "' expects " +
                         portTypeName(port->port) + ", but source '" + *target + "' gives " +
                         portTypeName(input.value()->output())};
        }
        return input;
    };

    create = [&](const Block& block) -> Result<const Source*> {
        if (const Source* existing = graph.find(block.name)) {
            return existing;
        }
        const KindSchema* kind = schema.find("source", block.kind);
        BlockReader reader(block, kind);
        if (kind == nullptr) {
            return Error{block.location.toString() + ": source '" + block.name +
                         "': unknown source kind '" + block.kind + "'"};
        }
        visiting.insert(block.name);
        Result<std::unique_ptr<Source>> made = Error{""};
        if (block.kind == "noise") {
            made = createNoise(block, reader);
        } else if (block.kind == "normal_map") {
            made = createNormalMap(block, reader, resolve);
        } else if (block.kind == "hypsometric") {
            made = createHypsometric(block, reader, resolve);
        } else {
            made = Error{block.location.toString() + ": source '" + block.name + "': kind '" +
                         block.kind + "' has no implementation in this build"};
        }
        visiting.erase(block.name);
        if (!made) {
            return made.error();
        }
        graph.sources_.push_back(std::move(made.value()));
        return graph.sources_.back().get();
    };

    for (const Block& block : model.sources) {
        Result<const Source*> made = create(block);
        if (!made) {
            return made.error();
        }
    }
    return graph;
}

Result<TerrainLayers> SourceGraph::terrainLayers(const ProjectModel& model, std::string_view scenario) {
    const Block* block = nullptr;
    if (scenario.empty()) {
        if (model.scenarios.empty()) {
            return Error{model.file.string() + ": the project has no scenario with terrain layers"};
        }
        block = &model.scenarios.front();
    } else {
        block = model.findScenario(scenario);
        if (block == nullptr) {
            return Error{model.file.string() + ": no scenario named '" + std::string(scenario) + "'"};
        }
    }
    BlockReader reader(*block, SchemaRegistry::builtin().find("scenario"));
    TerrainLayers layers;
    for (const std::string& name : reader.references("layers")) {
        const Source* source = find(name);
        if (source == nullptr) {
            return Error{reader.where("layers") + "unknown source '" + name + "'"};
        }
        const Source** slot = nullptr;
        switch (source->output()) {
            case PortType::Elevation: slot = &layers.elevation; break;
            case PortType::Image: slot = &layers.color; break;
            case PortType::Normals: slot = &layers.normals; break;
            default:
                return Error{reader.where("layers") + "source '" + name + "' gives " +
                             portTypeName(source->output()) +
                             ", which the terrain cannot draw yet (elevation, image or normals)"};
        }
        if (*slot != nullptr) {
            return Error{reader.where("layers") + "two " + portTypeName(source->output()) +
                         " layers ('" + (*slot)->name() + "' and '" + name +
                         "'); combine them with a blend source"};
        }
        *slot = source;
    }
    if (layers.elevation == nullptr) {
        return Error{reader.where("layers") + "scenario '" + block->name + "' has no elevation layer"};
    }
    if (layers.normals == nullptr) {
        const std::string derivedName = layers.elevation->name() + ".normals";
        if (const Source* existing = find(derivedName)) {
            layers.normals = existing;
        } else {
            sources_.push_back(std::make_unique<NormalMapSource>(derivedName, layers.elevation, 1.0));
            layers.normals = sources_.back().get();
        }
    }
    return layers;
}

}  // namespace sylva
