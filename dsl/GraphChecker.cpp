#include "GraphChecker.h"

#include <algorithm>
#include <functional>
#include <map>

#include "DiagnosticText.h"

namespace sylva::dsl {

GraphChecker::GraphChecker(const SchemaRegistry& schema, std::vector<Diagnostic>& diagnostics)
    : schema_(schema), diagnostics_(diagnostics) {}

void GraphChecker::findCycles(const std::vector<Block>& sources) {
    std::map<std::string, std::vector<Edge>> graph;
    std::map<std::string, std::size_t> order;
    for (const Block& source : sources) {
        order.emplace(source.name, order.size());
        std::vector<Edge>& edges = graph[source.name];
        for (const Attribute& attribute : source.attributes) {
            collectEdges(source.name, attribute.value, edges);
        }
    }
    // Depth first; meeting a source still on the path (colour 1) closes a cycle.
    std::map<std::string, int> colour;
    std::vector<Edge> path;
    std::function<void(const std::string&)> visit = [&](const std::string& node) {
        colour[node] = 1;
        for (const Edge& edge : graph[node]) {
            if (colour[edge.to] == 1) {
                reportCycle(closedCycle(path, edge), order);
            } else if (colour[edge.to] == 0 && order.count(edge.to)) {
                path.push_back(edge);
                visit(edge.to);
                path.pop_back();
            }
        }
        colour[node] = 2;
    };
    for (const Block& source : sources) {
        if (colour[source.name] == 0) {
            visit(source.name);
        }
    }
}

void GraphChecker::collectEdges(const std::string& from, const Value& value,
                                std::vector<Edge>& edges) {
    if (const Reference* reference = value.get<Reference>()) {
        if (reference->kind == "source") {
            edges.push_back({from, reference->name, value.location});
        }
    } else if (const ValueList* list = value.get<ValueList>()) {
        for (const Value& item : *list) {
            collectEdges(from, item, edges);
        }
    } else if (const ValueObject* object = value.get<ValueObject>()) {
        for (const auto& entry : *object) {
            collectEdges(from, entry.second, edges);
        }
    }
}

std::vector<GraphChecker::Edge> GraphChecker::closedCycle(const std::vector<Edge>& path,
                                                          const Edge& edge) {
    std::vector<Edge> cycle;
    for (std::size_t i = 0; i < path.size(); ++i) {
        if (path[i].from == edge.to) {
            cycle.assign(path.begin() + static_cast<std::ptrdiff_t>(i), path.end());
            break;
        }
    }
    cycle.push_back(edge);
    return cycle;
}

void GraphChecker::reportCycle(std::vector<Edge> cycle,
                               const std::map<std::string, std::size_t>& order) {
    auto first = std::min_element(cycle.begin(), cycle.end(), [&](const Edge& x, const Edge& y) {
        return order.at(x.from) < order.at(y.from);
    });
    std::rotate(cycle.begin(), first, cycle.end());
    std::string chain = cycle.front().from;
    for (const Edge& step : cycle) {
        chain += " -> " + step.to;
    }
    if (!reportedCycles_.insert(chain).second) {
        return;
    }
    Diagnostic& diagnostic =
        addError(diagnostics_, "E0301", "dependency cycle between sources", cycle.front().location,
                 "'" + cycle.front().from + "' uses '" + cycle.front().to + "' here");
    for (std::size_t i = 1; i < cycle.size(); ++i) {
        diagnostic.notes.push_back(
            {"'" + cycle[i].from + "' uses '" + cycle[i].to + "'", cycle[i].location});
    }
    diagnostic.cycle = chain;
}

void GraphChecker::checkPortTypes(const std::vector<Block>& sources) {
    for (const Block& source : sources) {
        const KindSchema* kindSchema = schema_.find("source", source.kind);
        if (!kindSchema) {
            continue;
        }
        for (const Attribute& attribute : source.attributes) {
            const AttributeSchema* attributeSchema = kindSchema->find(attribute.name);
            const Reference* reference = attribute.value.get<Reference>();
            if (!attributeSchema || !reference || reference->kind != "source" ||
                attributeSchema->port == PortType::None) {
                continue;
            }
            auto target = std::find_if(sources.begin(), sources.end(), [&](const Block& candidate) {
                return candidate.name == reference->name;
            });
            const KindSchema* targetSchema =
                target == sources.end() ? nullptr : schema_.find("source", target->kind);
            if (!targetSchema || targetSchema->output != PortType::None) {
                continue;  // declared outputs were checked where the reference was written
            }
            std::optional<PortType> output = outputOf(sources, reference->name, 0);
            if (!output || *output == attributeSchema->port) {
                continue;
            }
            const std::string key = source.name + "." + attribute.name + "@" +
                                    std::to_string(attribute.value.location.line) + ":" +
                                    std::to_string(attribute.value.location.column);
            if (!reportedPortErrors_.insert(key).second) {
                continue;  // the same attribute in another scenario's model
            }
            addError(diagnostics_, "E0406",
                     std::string("expected ") + portTypeName(attributeSchema->port) + ", found " +
                         portTypeName(*output),
                     attribute.value.location,
                     "'" + reference->name + "' is " + withArticle(target->kind) +
                         " source, which outputs " + portTypeName(*output));
        }
    }
}

std::optional<PortType> GraphChecker::outputOf(const std::vector<Block>& sources,
                                               const std::string& name, int depth) const {
    auto block = std::find_if(sources.begin(), sources.end(),
                              [&](const Block& candidate) { return candidate.name == name; });
    if (block == sources.end() || depth > 64) {
        return std::nullopt;  // an error already reported, or a cycle (reported by findCycles)
    }
    const KindSchema* kindSchema = schema_.find("source", block->kind);
    if (!kindSchema) {
        return std::nullopt;
    }
    const std::string_view decidedBy = schema_.outputFrom(block->kind);
    if (kindSchema->output != PortType::None || decidedBy.empty()) {
        return kindSchema->output == PortType::None ? std::nullopt
                                                    : std::optional(kindSchema->output);
    }
    const Attribute* decider = block->find(decidedBy);
    if (!decider) {
        return std::nullopt;
    }
    if (const Reference* reference = decider->value.get<Reference>()) {
        return outputOf(sources, reference->name, depth + 1);
    }
    if (const Word* word = decider->value.get<Word>()) {
        for (PortType type : {PortType::Elevation, PortType::Image, PortType::Normals,
                              PortType::Mask, PortType::Features, PortType::Instances}) {
            if (word->text == portTypeName(type)) {
                return type;
            }
        }
    }
    return std::nullopt;  // e.g. raster kind = auto: known once the file is opened
}

}  // namespace sylva::dsl
