// Evaluates expressions to plain Values: literals, lists and objects, @references (to
// params, substituted, and to fields of other blocks, evaluated where they are written),
// conditionals, indexing, field access, operators with their dimension rules and calls
// of the BuiltinFunctions. References are looked up from the scope the expression is
// written in. Problems are E0201 (unknown reference), E0210 (unknown field), E0212
// (param type), E0302 (a value depending on itself), E0401/E0402 (operand types),
// E0404 (index), E0408 (division by zero), E0409 (param without value).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "BuiltinFunctions.h"
#include "NameScope.h"
#include "ValueChecker.h"
#include "sylva/core/model/Value.h"
#include "sylva/dsl/Ast.h"
#include "sylva/dsl/Diagnostic.h"

namespace sylva::dsl {

class ExpressionEvaluator {
public:
    // `setPatches` (--set, by block) win over the attributes a block field reads.
    ExpressionEvaluator(NameScope& names, ValueChecker& values, const PatchesByBlock& setPatches,
                        std::vector<Diagnostic>& diagnostics);

    // The value of `expr` written in `scope`. `expectedTarget` is the block keyword a
    // reference should name ("source", "camera"; empty: any), for messages.
    std::optional<Value> evaluate(const Expr& expr, const std::string& scope,
                                  const std::string& expectedTarget);
    // The value of a param (evaluated once, on first use; `use` locates a cycle).
    std::optional<Value> evaluateParam(Declaration& param, const SourceLocation& use);

private:
    std::optional<Value> evaluate(const Expr& expr, const std::string& expectedTarget);
    std::optional<Value> evaluateConditional(const Expr& expr, const std::string& expectedTarget);
    std::optional<Value> evaluateIndex(const Expr& expr, const std::string& expectedTarget);
    std::optional<Value> evaluateList(const Expr& expr, const std::string& expectedTarget);
    std::optional<Value> evaluateObject(const Expr& expr);
    std::optional<Value> evaluateReference(const Expr& expr, const std::string& expectedTarget);
    void reportUnknownReference(const Expr& expr, const std::string& written,
                                const std::string& expectedTarget);
    std::optional<Value> evaluateBlockField(Declaration& declaration, const std::string& field,
                                            const SourceLocation& location);
    void reportUnknownBlockField(const Declaration& declaration, const std::string& field,
                                 const SourceLocation& location);
    std::optional<Value> fieldOf(const Value& value, const std::string& field,
                                 const SourceLocation& location);
    std::optional<Value> evaluateUnary(const Expr& expr);
    std::optional<Value> evaluateBinary(const Expr& expr);
    std::optional<Value> evaluateLogical(const Expr& expr, const Value& left, const Value& right);
    std::optional<Value> evaluateEquality(const Expr& expr, const Value& left, const Value& right);
    std::optional<Value> evaluateOrder(const Expr& expr, const Value& left, const Value& right);
    std::optional<Value> evaluateArithmetic(const Expr& expr, const Value& left,
                                            const Value& right);
    std::optional<Value> evaluateCall(const Expr& expr);

    NameScope& names_;
    ValueChecker& values_;
    const PatchesByBlock& setPatches_;
    std::vector<Diagnostic>& diagnostics_;
    BuiltinFunctions functions_;
    std::string scope_;                          // of the expression being evaluated
    std::vector<std::string> evaluatingFields_;  // "block.field" being evaluated (cycles)
};

}  // namespace sylva::dsl
