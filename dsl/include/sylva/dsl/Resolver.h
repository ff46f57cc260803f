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
#include <set>
#include <string>
#include <vector>

#include "sylva/core/model/ProjectModel.h"
#include "sylva/core/model/Schema.h"
#include "sylva/dsl/Ast.h"
#include "sylva/dsl/Diagnostic.h"

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

class Resolver {
public:
    Resolver(const SchemaRegistry& schema, std::vector<Diagnostic>& diagnostics);

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
    struct Declaration {
        std::string keyword;  // "param", "source", "camera" ...
        std::string name;     // qualified: "ns.forest"
        std::string kind;
        std::string scope;
        SourceLocation location;
        const BlockNode* block = nullptr;
        const ParamNode* param = nullptr;
        const KindSchema* schema = nullptr;
        // For params:
        const Expr* valueExpr = nullptr;
        std::string valueScope;  // scope the value expression is evaluated in
        std::optional<Value> value;
        int state = 0;  // 0 not evaluated, 1 evaluating, 2 done
        bool used = false;
        // For scenarios: the effective state after `extends`.
        int scenarioState = 0;
        std::optional<Block> scenarioBlock;
        std::vector<std::pair<std::string, const AttributeNode*>> overrideAttributes;
        std::vector<std::string> overrideScopes;
    };
    // An attribute written somewhere else that replaces the block's own (override, --set).
    struct Patch {
        const AttributeNode* attribute = nullptr;
        std::string scope;
    };
    struct BlockEntry {
        const BlockNode* node = nullptr;
        const KindSchema* schema = nullptr;
        std::string scope;
    };

    void declare(const Statement& statement, const std::string& scope);
    bool addName(Declaration declaration);
    void applyDefines(const std::vector<DefineNode>& defines);
    std::optional<Value> evaluateParam(Declaration& param, const SourceLocation& use);
    std::optional<Block> checkBlock(const BlockEntry& entry, const std::vector<Patch>& patches,
                                    const Block* inherited = nullptr);
    void fillDefaults(Block& block, const KindSchema& schema,
                      const std::vector<std::string>& written = {});
    void findCycles(const std::vector<Block>& sources);
    // Port types of references to sources whose output follows their attributes
    // (KindSchema::outputFrom), checked on the finished graph of one model.
    void checkPortTypes(const std::vector<Block>& sources);
    std::optional<PortType> outputOf(const std::vector<Block>& sources, const std::string& name,
                                     int depth) const;
    std::string describeBlock(const KindSchema& schema) const;
    void resolveScenario(Declaration& scenario);
    void rebasePath(const AttributeNode& attribute, Value& value) const;
    Declaration* lookup(const std::string& scope, const std::string& written,
                        std::vector<std::string>* fields);

    std::optional<Value> evaluate(const Expr& expr, const std::string& expectedTarget);
    std::optional<Value> evaluateReference(const Expr& expr, const std::string& expectedTarget);
    std::optional<Value> evaluateBlockField(Declaration& declaration, const std::string& field,
                                            const SourceLocation& location);
    std::optional<Value> fieldOf(const Value& value, const std::string& field,
                                 const SourceLocation& location);
    std::optional<Value> evaluateUnary(const Expr& expr);
    std::optional<Value> evaluateBinary(const Expr& expr);
    std::optional<Value> evaluateCall(const Expr& expr);
    std::optional<Value> evaluateGeo(const Expr& expr, std::vector<Value> arguments);
    std::optional<Value> coerce(Value value, const AttributeSchema& schema,
                                const std::string& what);
    std::optional<double> coerceAngle(const Value& value, const std::string& what);

    const SchemaRegistry& schema_;
    std::vector<Diagnostic>& diagnostics_;
    ResolveOptions options_;
    std::vector<Declaration> declarations_;
    std::map<std::string, std::size_t, std::less<>> names_;
    std::vector<BlockEntry> blocks_;  // to check, in order
    const BlockNode* project_ = nullptr;
    std::optional<Value> projectCrs_;  // project { crs = "..." }, once checked and valid
    bool projectCrsInvalid_ = false;   // a crs was written but cannot be used (already reported)
    const BlockNode* render_ = nullptr;
    std::vector<std::unique_ptr<BlockNode>> implicit_;  // project/render the files omit
    std::filesystem::path rootDirectory_;               // of the project file, for rebasePath
    std::string scope_;                                 // scope of the expression being evaluated
    std::vector<std::string> evaluatingFields_;         // "block.field" being evaluated (cycles)
    std::set<std::string> reportedCycles_;
    std::set<std::string> reportedPortErrors_;
    std::map<std::string, std::vector<Patch>> setPatches_;  // --set, by block name
};

// "2500m", "30deg", "80%", "20s", "320px", "7": a quantity in the units users write.
std::string formatQuantity(const Quantity& quantity);

}  // namespace sylva::dsl
