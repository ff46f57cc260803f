// Checks the source graph of one finished model: dependency cycles among sources
// (E0301, each cycle reported once however many scenario models contain it) and the
// port types of references to sources whose output follows their attributes
// (KindSchema::outputFrom; E0406, each attribute reported once). References to sources
// with a fixed output are checked where they are written (ValueChecker).
#pragma once

#include <cstddef>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "sylva/core/model/ProjectModel.h"
#include "sylva/core/model/Schema.h"
#include "sylva/dsl/Diagnostic.h"

namespace sylva::dsl {

class GraphChecker {
public:
    GraphChecker(const SchemaRegistry& schema, std::vector<Diagnostic>& diagnostics);

    void findCycles(const std::vector<Block>& sources);
    void checkPortTypes(const std::vector<Block>& sources);

private:
    struct Edge {
        std::string from;
        std::string to;
        SourceLocation location;  // of the reference
    };
    // The references of `value` (and of lists and objects inside it) to sources.
    static void collectEdges(const std::string& from, const Value& value, std::vector<Edge>& edges);
    // The cycle `edge` closes: the part of the depth-first `path` from where it first
    // left edge.to, then `edge`.
    static std::vector<Edge> closedCycle(const std::vector<Edge>& path, const Edge& edge);
    // Reports `cycle` once, starting at the source declared first (`order`: declaration
    // index by name), so the report is stable.
    void reportCycle(std::vector<Edge> cycle, const std::map<std::string, std::size_t>& order);
    // The port type source `name` outputs, following the attribute that decides it; nullopt
    // when unknown until the graph is built (or after an error reported elsewhere).
    std::optional<PortType> outputOf(const std::vector<Block>& sources, const std::string& name,
                                     int depth) const;

    const SchemaRegistry& schema_;
    std::vector<Diagnostic>& diagnostics_;
    std::set<std::string> reportedCycles_;
    std::set<std::string> reportedPortErrors_;
};

}  // namespace sylva::dsl
