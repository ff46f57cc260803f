// The checker: binds names (order-free), evaluates expressions to plain Values
// (constant folding, @param substitution, dimension checks), checks every block against
// the SchemaRegistry, fills defaults, finds dependency cycles among sources and builds
// the ProjectModel. Problems are appended to the diagnostics (E02xx-E04xx, W0xxx);
// resolve() returns a model only when no error was reported.
#pragma once

#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "sylva/core/scene/ProjectModel.h"
#include "sylva/core/schema/Schema.h"
#include "sylva/dsl/Ast.h"
#include "sylva/dsl/Diagnostic.h"

namespace sylva::dsl {

// A `-D name=value` from the command line, already parsed.
struct DefineNode {
    std::string name;
    SourceLocation nameLocation;
    ExprPtr value;  // null if the value did not parse (already reported)
};

class Resolver {
public:
    Resolver(const SchemaRegistry& schema, std::vector<Diagnostic>& diagnostics);

    std::optional<ProjectModel> resolve(const FileNode& file,
                                        const std::vector<DefineNode>& defines,
                                        const std::filesystem::path& path);

private:
    struct Declaration {
        std::string keyword;  // "param", "source", "camera" ...
        std::string name;
        std::string kind;
        SourceLocation location;
        const BlockNode* block = nullptr;
        const ParamNode* param = nullptr;
        const KindSchema* schema = nullptr;
        // For params:
        const Expr* valueExpr = nullptr;
        std::optional<Value> value;
        int state = 0;  // 0 not evaluated, 1 evaluating, 2 done
        bool used = false;
    };

    void declare(const Statement& statement);
    bool addName(Declaration declaration);
    void applyDefines(const std::vector<DefineNode>& defines);
    std::optional<Value> evaluateParam(Declaration& param, const SourceLocation& use);
    std::optional<Block> checkBlock(const BlockNode& node, const KindSchema& schema);
    void fillDefaults(Block& block, const KindSchema& schema,
                      const std::vector<std::string>& written = {});
    void findCycles(const std::vector<Block>& sources);
    std::string describeBlock(const KindSchema& schema) const;

    std::optional<Value> evaluate(const Expr& expr, const std::string& expectedTarget);
    std::optional<Value> evaluateReference(const Expr& expr, const std::string& expectedTarget);
    std::optional<Value> evaluateUnary(const Expr& expr);
    std::optional<Value> evaluateBinary(const Expr& expr);
    std::optional<Value> evaluateCall(const Expr& expr);
    std::optional<Value> coerce(Value value, const AttributeSchema& schema,
                                const std::string& what);
    std::optional<double> coerceAngle(const Value& value, const std::string& what);

    const SchemaRegistry& schema_;
    std::vector<Diagnostic>& diagnostics_;
    std::vector<Declaration> declarations_;
    std::map<std::string, std::size_t, std::less<>> names_;
    std::vector<std::pair<const BlockNode*, const KindSchema*>> blocks_;  // to check, in order
    const BlockNode* project_ = nullptr;
    const BlockNode* render_ = nullptr;
};

// "2500m", "30deg", "80%", "20s", "320px", "7": a quantity in the units users write.
std::string formatQuantity(const Quantity& quantity);

}  // namespace sylva::dsl
