#include "sylva/core/sources/graph/SourceGraph.h"

#include <algorithm>
#include <functional>
#include <map>
#include <set>

#include "sylva/core/model/BlockReader.h"
#include "sylva/core/sources/graph/SourceFactory.h"
#include "sylva/core/sources/objects/MeshSource.h"
#include "sylva/core/sources/plants/PlantsSource.h"
#include "sylva/core/sources/raster/NormalMapSource.h"
#include "sylva/core/sources/raster/RasterSource.h"

namespace sylva {
namespace {

// Builds the sources of a model depth-first: a source's inputs are created (and their
// ports checked against the schema) before it; a source met again while it is being
// created closes a dependency cycle.
class GraphBuilder {
public:
    // `sources`: the graph's own list, which `graph.find` searches.
    GraphBuilder(const ProjectModel& model, const SourceGraph& graph,
                 std::vector<std::unique_ptr<Source>>& sources)
        : schema_(SchemaRegistry::builtin()),
          graph_(graph),
          sources_(sources),
          projectFolder_(model.file.has_parent_path() ? model.file.parent_path()
                                                      : std::filesystem::path(".")) {
        for (const Block& block : model.sources) {
            blocks_.emplace(block.name, &block);
        }
    }

    Result<const Source*> create(const Block& block) {
        if (const Source* existing = graph_.find(block.name)) {
            return existing;
        }
        const KindSchema* kind = schema_.find("source", block.kind);
        BlockReader reader(block, kind);
        if (kind == nullptr) {
            return Error{block.location.toString() + ": source '" + block.name +
                         "': unknown source kind '" + block.kind + "'"};
        }
        const SourceCreator creator = findSourceCreator(block.kind);
        if (creator == nullptr) {
            return Error{block.location.toString() + ": source '" + block.name + "': kind '" +
                         block.kind + "' has no implementation in this build"};
        }
        visiting_.insert(block.name);
        const InputResolver input = [&](std::string_view attribute, bool required) {
            return resolve(reader, attribute, required);
        };
        const InputListResolver inputList =
            [&](std::string_view attribute) -> Result<std::vector<const Source*>> {
            std::vector<const Source*> sources;
            for (const std::string& name : reader.references(attribute)) {
                Result<const Source*> source = resolveNamed(reader, attribute, name);
                if (!source) {
                    return source.error();
                }
                sources.push_back(source.value());
            }
            return sources;
        };
        const SourceBuildContext context{block, reader, input, projectFolder_, &inputList};
        Result<std::unique_ptr<Source>> made = creator(context);
        visiting_.erase(block.name);
        if (!made) {
            return made.error();
        }
        sources_.push_back(std::move(made.value()));
        return sources_.back().get();
    }

private:
    Result<const Source*> resolve(const BlockReader& reader, std::string_view attribute,
                                  bool required) {
        std::optional<std::string> target = reader.reference(attribute);
        if (!target) {
            if (required) {
                return Error{reader.where(attribute) + "missing input '" + std::string(attribute) +
                             "'"};
            }
            return static_cast<const Source*>(nullptr);
        }
        return resolveNamed(reader, attribute, *target);
    }

    Result<const Source*> resolveNamed(const BlockReader& reader, std::string_view attribute,
                                       const std::string& target) {
        auto it = blocks_.find(target);
        if (it == blocks_.end()) {
            return Error{reader.where(attribute) + "unknown source '" + target + "'"};
        }
        if (visiting_.count(target) != 0) {
            return Error{reader.where(attribute) + "dependency cycle through source '" + target +
                         "'"};
        }
        Result<const Source*> input = create(*it->second);
        if (!input) {
            return input;
        }
        const KindSchema* kind = schema_.find("source", reader.block().kind);
        const AttributeSchema* port = kind ? kind->find(attribute) : nullptr;
        if (port != nullptr && port->port != PortType::None &&
            input.value()->output() != port->port) {
            return Error{reader.where(attribute) + "'" + std::string(attribute) + "' expects " +
                         portTypeName(port->port) + ", but source '" + target + "' gives " +
                         portTypeName(input.value()->output())};
        }
        return input;
    }

    const SchemaRegistry& schema_;
    const SourceGraph& graph_;
    std::vector<std::unique_ptr<Source>>& sources_;
    const std::filesystem::path projectFolder_;
    std::map<std::string, const Block*, std::less<>> blocks_;
    std::set<std::string, std::less<>> visiting_;
};

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
    SourceGraph graph;
    GraphBuilder builder(model, graph, graph.sources_);
    for (const Block& block : model.sources) {
        Result<const Source*> made = builder.create(block);
        if (!made) {
            return made.error();
        }
    }
    return graph;
}

Result<TerrainLayers> SourceGraph::terrainLayers(const ProjectModel& model,
                                                 std::string_view scenario) {
    const Block* block = nullptr;
    if (scenario.empty()) {
        if (model.scenarios.empty()) {
            return Error{model.file.string() + ": the project has no scenario with terrain layers"};
        }
        block = &model.scenarios.front();
    } else {
        block = model.findScenario(scenario);
        if (block == nullptr) {
            return Error{model.file.string() + ": no scenario named '" + std::string(scenario) +
                         "'"};
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
            case PortType::Elevation:
                slot = &layers.elevation;
                break;
            case PortType::Image:
                slot = &layers.color;
                break;
            case PortType::Normals:
                slot = &layers.normals;
                break;
            case PortType::Instances:
                if (const PlantsSource* plants = PlantsSource::from(source)) {
                    layers.plants.push_back(plants);
                    continue;
                }
                [[fallthrough]];
            case PortType::Meshes:
                if (const MeshSource* meshes = MeshSource::from(source)) {
                    layers.meshes.push_back(meshes);
                    continue;
                }
                [[fallthrough]];
            default:
                return Error{
                    reader.where("layers") + "source '" + name + "' gives " +
                    portTypeName(source->output()) +
                    ", which a scenario cannot draw (elevation, image, normals, plants or meshes)"};
        }
        if (*slot != nullptr) {
            return Error{reader.where("layers") + "two " + portTypeName(source->output()) +
                         " layers ('" + (*slot)->name() + "' and '" + name +
                         "'); combine them with a blend source"};
        }
        *slot = source;
    }
    if (layers.elevation == nullptr) {
        return Error{reader.where("layers") + "scenario '" + block->name +
                     "' has no elevation layer"};
    }
    if (layers.normals == nullptr) {
        const std::string derivedName = layers.elevation->name() + ".normals";
        if (const Source* existing = find(derivedName)) {
            layers.normals = existing;
        } else {
            sources_.push_back(
                std::make_unique<NormalMapSource>(derivedName, layers.elevation, 1.0));
            layers.normals = sources_.back().get();
        }
    }
    return layers;
}

namespace {

void collect(const Source& source, std::unordered_set<const Source*>& seen) {
    if (seen.insert(&source).second) {
        for (const Source* input : source.inputs()) {
            if (input != nullptr) {
                collect(*input, seen);
            }
        }
        // A raster's coverage mask is not an input of anything (blend asks for it
        // through BlendSource::coverageOf), but its tiles are live all the same.
        if (const auto* raster = dynamic_cast<const RasterSource*>(&source);
            raster && raster->coverage()) {
            collect(*raster->coverage(), seen);
        }
    }
}

}  // namespace

std::unordered_set<std::uint64_t> SourceGraph::contentHashes() const {
    std::unordered_set<const Source*> all;
    for (const auto& source : sources_) {
        collect(*source, all);
    }
    std::unordered_set<std::uint64_t> hashes;
    for (const Source* source : all) {
        hashes.insert(source->contentHash());
    }
    return hashes;
}

std::vector<std::filesystem::path> SourceGraph::files() const {
    std::unordered_set<const Source*> all;
    for (const auto& source : sources_) {
        collect(*source, all);
    }
    std::vector<std::filesystem::path> result;
    for (const Source* source : all) {
        for (const std::filesystem::path& file : source->files()) {
            result.push_back(file);
        }
    }
    std::sort(result.begin(), result.end());
    result.erase(std::unique(result.begin(), result.end()), result.end());
    return result;
}

}  // namespace sylva
