// The names of a project: every param and named block of every parsed file, qualified
// by the namespace of its import ("ns.forest"), declared in any order and looked up from
// the scope an expression is written in. Declaring reports the problems of a block's
// head (E0202-E0206, E0214); applying -D reports undeclared params (E0207). Also holds
// what later steps keep per name: the value of a param, the state of a scenario.
#pragma once

#include <cstddef>
#include <functional>
#include <initializer_list>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "sylva/core/model/ProjectModel.h"
#include "sylva/core/model/Schema.h"
#include "sylva/dsl/Ast.h"
#include "sylva/dsl/Diagnostic.h"
#include "sylva/dsl/Resolver.h"

namespace sylva::dsl {

// Where evaluation of a param or scenario stands (cycles are found by meeting Evaluating).
enum class EvaluationState { NotStarted, Evaluating, Done };

// One declared name: a param or a named block.
struct Declaration {
    std::string keyword;  // "param", "source", "camera" ...
    std::string name;     // qualified: "ns.forest"
    std::string kind;
    std::string scope;
    SourceLocation location;
    const BlockNode* block = nullptr;
    const ParamNode* param = nullptr;
    const KindSchema* schema = nullptr;  // nullptr when the kind is unknown (reported)
    // For params: the expression giving the value (the default, or -D) and the scope it
    // is evaluated in, then the value once evaluated (nullopt after an error).
    const Expr* valueExpr = nullptr;
    std::string valueScope;
    std::optional<Value> value;
    EvaluationState state = EvaluationState::NotStarted;
    bool used = false;
    // For scenarios: the effective block after `extends`, and the overrides in force
    // (inherited ones first) as (target block, attribute) with the scope they are written in.
    EvaluationState scenarioState = EvaluationState::NotStarted;
    std::optional<Block> scenarioBlock;
    std::vector<std::pair<std::string, const AttributeNode*>> overrideAttributes;
    std::vector<std::string> overrideScopes;
};

// An attribute written somewhere else that replaces the block's own (override, --set),
// with the scope its expression is evaluated in.
struct Patch {
    const AttributeNode* attribute = nullptr;
    std::string scope;
};

// --set patches by qualified block name ("project" and "render" for those blocks).
using PatchesByBlock = std::map<std::string, std::vector<Patch>>;

// A block to check: its syntax, its schema and the scope of its expressions.
struct BlockEntry {
    const BlockNode* node = nullptr;
    const KindSchema* schema = nullptr;
    std::string scope;
};

class NameScope {
public:
    NameScope(const SchemaRegistry& schema, std::vector<Diagnostic>& diagnostics);

    // Declares every statement of every unit, in order. Declarations do not move
    // afterwards: pointers to them stay valid for the NameScope's life.
    void declareAll(const std::vector<ParsedUnit>& units);
    // Replaces the values of the params -D names (E0207 for names that are no param).
    void applyDefines(const std::vector<DefineNode>& defines);

    // The declaration `written` refers to from `scope`: the longest dotted prefix that
    // names something; the rest goes into `fields`. nullptr when nothing matches.
    Declaration* lookup(const std::string& scope, const std::string& written,
                        std::vector<std::string>* fields);
    // By qualified name; nullptr when undeclared.
    Declaration* find(std::string_view name);
    const Declaration* find(std::string_view name) const;
    // Qualified names of the declarations whose keyword is one of `keywords`, in order.
    std::vector<std::string> namesOf(std::initializer_list<std::string_view> keywords) const;
    // "did you mean 'SHOWN' (defined at file:line:col)?" for the declared `name`.
    std::string suggestion(const std::string& shown, const std::string& name) const;

    std::vector<Declaration>& declarations() { return declarations_; }
    const std::vector<Declaration>& declarations() const { return declarations_; }
    // The blocks to check, in declaration order (project and render included).
    std::vector<BlockEntry>& blocks() { return blocks_; }
    // The project / render block of the files; nullptr when they omit it.
    const BlockNode* project() const { return project_; }
    const BlockNode* render() const { return render_; }

private:
    void declare(const Statement& statement, const std::string& scope);
    void declareParam(const ParamNode& param, const std::string& scope);
    void declareBlock(const BlockNode& block, const std::string& scope);
    // A block keyword of the schema (E0203 otherwise).
    bool isKeyword(const BlockNode& block);
    // `extends` and `override` belong to scenarios only (E0214).
    void checkScenarioSyntax(const BlockNode& block);
    // The schema of a source block; false when the block cannot be declared at all.
    bool sourceSchema(const BlockNode& block, const KindSchema*& kindSchema);
    // project / render: at most one each, without a name.
    void declareAnonymous(const BlockNode& block, const KindSchema* kindSchema,
                          const std::string& scope);
    bool add(Declaration declaration);

    const SchemaRegistry& schema_;
    std::vector<Diagnostic>& diagnostics_;
    std::vector<std::string> keywords_;  // block keywords of the schema, in order
    std::vector<Declaration> declarations_;
    std::map<std::string, std::size_t, std::less<>> names_;  // into declarations_
    std::vector<BlockEntry> blocks_;
    const BlockNode* project_ = nullptr;
    const BlockNode* render_ = nullptr;
};

}  // namespace sylva::dsl
