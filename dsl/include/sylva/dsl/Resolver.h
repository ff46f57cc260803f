// The checker: binds names (order-free), evaluates expressions to plain Values
// (constant folding, @param substitution, dimension checks), checks every block against
// the SchemaRegistry, fills defaults, finds dependency cycles among sources and builds
// the ProjectModel. Problems are appended to the diagnostics (E02xx-E04xx, W0xxx);
// resolve() returns a model only when no error was reported.
#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "sylva/core/model/ProjectModel.h"
#include "sylva/core/model/Schema.h"
#include "sylva/dsl/Ast.h"
#include "sylva/dsl/Diagnostic.h"
#include "sylva/dsl/QuantityText.h"  // formatQuantity, declared here before

namespace sylva::dsl {

// A `-D name=value` from the command line, already parsed.
struct DefineNode {
    std::string name;
    SourceLocation nameLocation;
    ExprPtr value;  // null if the value did not parse (already reported)
};

// One parsed file of the project with the namespace its names live under ("" for the
// project file itself and for imports without `as`, "ns." for `import ... as ns`).
struct ParsedUnit {
    const FileNode* file = nullptr;
    std::string scope;
};

// A `--set block.attribute=value` from the command line, already parsed.
struct SetNode {
    std::string block;  // qualified block name, or "project" / "render"
    SourceLocation blockLocation;
    AttributeNode attribute;
};

struct ResolveOptions {
    bool lenient = false;  // unknown attributes are warnings (W0102), not errors
};

class NameScope;
class ValueChecker;
class ExpressionEvaluator;
class BlockChecker;
class GraphChecker;
struct Declaration;
struct Patch;

// The orchestrator of the checks. Its parts (private headers in dsl/: NameScope,
// ExpressionEvaluator with BuiltinFunctions, ValueChecker, BlockChecker, GraphChecker)
// are made afresh by each resolve().
class Resolver {
public:
    Resolver(const SchemaRegistry& schema, std::vector<Diagnostic>& diagnostics);
    ~Resolver();

    // One model per scenario in declaration order (one model with an empty scenario name
    // when the project has none); empty when an error was reported.
    std::vector<ProjectModel> resolve(const std::vector<ParsedUnit>& units,
                                      const std::vector<DefineNode>& defines,
                                      const std::vector<SetNode>& sets,
                                      const std::filesystem::path& path,
                                      const ResolveOptions& options = {});
    // The single-file form used by older callers: the first model, if any.
    std::optional<ProjectModel> resolve(const FileNode& file,
                                        const std::vector<DefineNode>& defines,
                                        const std::filesystem::path& path);

private:
    // The steps of resolve(), in order.
    void collectSets(const std::vector<SetNode>& sets);
    void evaluateParams();
    void addImplicitBlocks();
    ProjectModel checkBlocks(const std::filesystem::path& path);
    void addToModel(ProjectModel& model, Block block);
    void acceptProjectCrs(const Block& project);
    std::vector<Declaration*> resolveScenarios(ProjectModel& model);
    void resolveScenario(Declaration& scenario);
    // Sets `inherited` to the block of the scenario `extends` names (resolved first;
    // stays nullptr without `extends` or after an error reported here). False when the
    // parent has errors of its own: the scenario is then not checked.
    bool resolveParent(Declaration& scenario, const Block*& inherited);
    void collectOverrides(Declaration& scenario);
    void addOmittedBlocks(ProjectModel& model, const std::filesystem::path& path);
    void collectParams(ProjectModel& model);
    void reportUnusedSources(const std::vector<ProjectModel>& models);
    std::vector<ProjectModel> scenarioModels(ProjectModel model,
                                             const std::vector<Declaration*>& scenarios);
    // Applies the overrides of `scenario` to its copy of the model; the names of the
    // blocks they change.
    std::vector<std::string> applyOverrides(ProjectModel& model, const Declaration& scenario);
    const std::vector<Patch>& setPatchesOf(const std::string& block) const;
    Block renderBlockWith(const std::vector<Patch>& patches);

    const SchemaRegistry& schema_;
    std::vector<Diagnostic>& diagnostics_;
    std::unique_ptr<NameScope> names_;
    std::map<std::string, std::vector<Patch>> setPatches_;  // --set, by block name
    std::unique_ptr<ValueChecker> values_;
    std::unique_ptr<ExpressionEvaluator> expressions_;
    std::unique_ptr<BlockChecker> blocks_;
    std::unique_ptr<GraphChecker> graph_;
    std::vector<std::unique_ptr<BlockNode>> implicit_;  // project/render the files omit
};

}  // namespace sylva::dsl
