#include "ExpressionEvaluator.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "DiagnosticText.h"
#include "MakeValue.h"
#include "sylva/dsl/EditDistance.h"
#include "sylva/dsl/ModelHash.h"

namespace sylva::dsl {

namespace {

const std::vector<std::string> kParamTypes = {"number",     "length", "angle", "time",
                                              "percentage", "string", "bool",  "colour"};

// The schema a typed param's value is checked against; false for an unknown type.
bool paramTypeSchema(const std::string& type, AttributeSchema& schema) {
    static const std::pair<const char*, Dimension> kNumbers[] = {{"number", Dimension::None},
                                                                 {"length", Dimension::Length},
                                                                 {"angle", Dimension::Angle},
                                                                 {"time", Dimension::Time},
                                                                 {"percentage", Dimension::Ratio}};
    for (const auto& [name, dimension] : kNumbers) {
        if (type == name) {
            schema.type = ValueType::Number;
            schema.dimension = dimension;
            return true;
        }
    }
    if (type == "string") {
        schema.type = ValueType::String;
    } else if (type == "bool") {
        schema.type = ValueType::Bool;
    } else if (type == "colour" || type == "color") {
        schema.type = ValueType::Color;
    } else {
        return false;
    }
    return true;
}

const char* operatorText(char op) {
    switch (op) {
        case 'l':
            return "<=";
        case 'g':
            return ">=";
        case 'e':
            return "==";
        case 'n':
            return "!=";
        case '&':
            return "&&";
        case '|':
            return "||";
        case '<':
            return "<";
        case '>':
            return ">";
        case '%':
            return "%";
        default:
            return "?";
    }
}

bool isReferenceLike(const AttributeSchema& schema) {
    return schema.type == ValueType::Reference ||
           (schema.type == ValueType::List && schema.element == ValueType::Reference);
}

}  // namespace

ExpressionEvaluator::ExpressionEvaluator(NameScope& names, ValueChecker& values,
                                         const PatchesByBlock& setPatches,
                                         std::vector<Diagnostic>& diagnostics)
    : names_(names),
      values_(values),
      setPatches_(setPatches),
      diagnostics_(diagnostics),
      functions_(values, diagnostics) {}

std::optional<Value> ExpressionEvaluator::evaluate(const Expr& expr, const std::string& scope,
                                                   const std::string& expectedTarget) {
    std::string saved = std::exchange(scope_, scope);
    std::optional<Value> value = evaluate(expr, expectedTarget);
    scope_ = saved;
    return value;
}

std::optional<Value> ExpressionEvaluator::evaluateParam(Declaration& param,
                                                        const SourceLocation& use) {
    if (param.state == EvaluationState::Done) {
        return param.value;
    }
    if (param.state == EvaluationState::Evaluating) {
        addError(diagnostics_, "E0302", "param '" + param.name + "' depends on itself", use,
                 "used while computing its own value");
        return std::nullopt;
    }
    param.state = EvaluationState::Evaluating;
    std::optional<Value> value;
    AttributeSchema typeSchema;
    bool typed = !param.param->type.empty();
    if (typed && !paramTypeSchema(param.param->type, typeSchema)) {
        Diagnostic& diagnostic =
            addError(diagnostics_, "E0212", "unknown param type '" + param.param->type + "'",
                     param.param->typeLocation, "not a type");
        if (auto match = closestMatch(param.param->type, kParamTypes)) {
            diagnostic.help.push_back("did you mean '" + *match + "'?");
        }
        diagnostic.help.push_back("types are: " + join(kParamTypes));
    } else if (!param.valueExpr) {
        addError(diagnostics_, "E0409", "param '" + param.name + "' has no value", param.location,
                 "declared without a default")
            .help.push_back("give it a default ('param " + param.name +
                            " = ...') or set it with -D " + param.name + "=...");
    } else {
        value = evaluate(*param.valueExpr, param.valueScope, "");
        if (value && typed) {
            value = values_.coerce(std::move(*value), typeSchema, "param '" + param.name + "'");
        }
    }
    param.state = EvaluationState::Done;
    param.value = value;
    return value;
}

std::optional<Value> ExpressionEvaluator::evaluate(const Expr& expr,
                                                   const std::string& expectedTarget) {
    switch (expr.kind) {
        case Expr::Kind::Number:
            return makeValue(Quantity{expr.number, expr.dimension}, expr.location);
        case Expr::Kind::String:
            return makeValue(expr.text, expr.location);
        case Expr::Kind::Color:
            return makeValue(expr.color, expr.location);
        case Expr::Kind::Bool:
            return makeValue(expr.boolean, expr.location);
        case Expr::Kind::Word:
            return makeValue(Word{expr.text}, expr.location);
        case Expr::Kind::DateTime:
            return makeValue(expr.text, expr.location);
        case Expr::Kind::Conditional:
            return evaluateConditional(expr, expectedTarget);
        case Expr::Kind::Index:
            return evaluateIndex(expr, expectedTarget);
        case Expr::Kind::Field: {
            std::optional<Value> object = evaluate(*expr.children[0], "");
            if (!object) {
                return std::nullopt;
            }
            return fieldOf(*object, expr.text, expr.location);
        }
        case Expr::Kind::Reference:
            return evaluateReference(expr, expectedTarget);
        case Expr::Kind::Unary:
            return evaluateUnary(expr);
        case Expr::Kind::Binary:
            return evaluateBinary(expr);
        case Expr::Kind::Call:
            return evaluateCall(expr);
        case Expr::Kind::List:
            return evaluateList(expr, expectedTarget);
        case Expr::Kind::Object:
            return evaluateObject(expr);
    }
    return std::nullopt;
}

std::optional<Value> ExpressionEvaluator::evaluateConditional(const Expr& expr,
                                                              const std::string& expectedTarget) {
    std::optional<Value> condition = evaluate(*expr.children[0], "");
    std::optional<Value> then = evaluate(*expr.children[1], expectedTarget);
    std::optional<Value> otherwise = evaluate(*expr.children[2], expectedTarget);
    if (!condition || !then || !otherwise) {
        return std::nullopt;
    }
    const bool* flag = condition->get<bool>();
    if (!flag) {
        addError(diagnostics_, "E0402", "expected bool, found " + condition->typeName(),
                 condition->location, "a condition must be true or false");
        return std::nullopt;
    }
    Value chosen = *flag ? std::move(*then) : std::move(*otherwise);
    return chosen;
}

std::optional<Value> ExpressionEvaluator::evaluateIndex(const Expr& expr,
                                                        const std::string& expectedTarget) {
    std::optional<Value> container = evaluate(*expr.children[0], expectedTarget);
    std::optional<Value> index = evaluate(*expr.children[1], "");
    if (!container || !index) {
        return std::nullopt;
    }
    if (const std::string* key = index->get<std::string>()) {
        return fieldOf(*container, *key, expr.location);
    }
    const ValueList* list = container->get<ValueList>();
    const Quantity* position = index->get<Quantity>();
    if (!list || !position || position->dimension != Dimension::None) {
        addError(diagnostics_, "E0402",
                 "cannot index " + withArticle(container->typeName()) + " with " +
                     withArticle(index->typeName()),
                 expr.location, "write list[number] or object[\"key\"]");
        return std::nullopt;
    }
    double at = position->value;
    if (at < 0 || at != std::floor(at) || at >= static_cast<double>(list->size())) {
        addError(diagnostics_, "E0404", "index out of range", index->location,
                 formatNumber(at) + " is not in [0, " + std::to_string(list->size()) + ")");
        return std::nullopt;
    }
    Value element = (*list)[static_cast<std::size_t>(at)];
    element.location = expr.location;
    return element;
}

std::optional<Value> ExpressionEvaluator::evaluateList(const Expr& expr,
                                                       const std::string& expectedTarget) {
    ValueList list;
    bool ok = true;
    for (const ExprPtr& child : expr.children) {
        std::optional<Value> element = evaluate(*child, expectedTarget);
        if (element) {
            list.push_back(std::move(*element));
        } else {
            ok = false;
        }
    }
    return ok ? std::optional<Value>(makeValue(std::move(list), expr.location)) : std::nullopt;
}

std::optional<Value> ExpressionEvaluator::evaluateObject(const Expr& expr) {
    ValueObject object;
    bool ok = true;
    for (std::size_t i = 0; i < expr.children.size(); ++i) {
        const std::string& key = expr.keys[i].first;
        const SourceLocation& keyLocation = expr.keys[i].second;
        auto first = std::find_if(object.begin(), object.end(),
                                  [&](const auto& entry) { return entry.first == key; });
        if (first != object.end()) {
            addError(diagnostics_, "E0209", "duplicate key '" + key + "'", keyLocation,
                     "'" + key + "' is already set in this object")
                .notes.push_back({"first set here", first->second.location});
            ok = false;
            continue;
        }
        std::optional<Value> value = evaluate(*expr.children[i], "");
        if (value) {
            object.emplace_back(key, std::move(*value));
        } else {
            ok = false;
        }
    }
    return ok ? std::optional<Value>(makeValue(std::move(object), expr.location)) : std::nullopt;
}

std::optional<Value> ExpressionEvaluator::evaluateReference(const Expr& expr,
                                                            const std::string& expectedTarget) {
    const std::string written = expr.text + (expr.field.empty() ? "" : "." + expr.field);
    std::vector<std::string> fields;
    Declaration* found = names_.lookup(scope_, written, &fields);
    if (!found) {
        reportUnknownReference(expr, written, expectedTarget);
        return std::nullopt;
    }
    Declaration& declaration = *found;
    std::optional<Value> value;
    std::size_t next = 0;
    if (declaration.keyword == "param") {
        declaration.used = true;
        value = evaluateParam(declaration, expr.location);
    } else if (fields.empty()) {
        return makeValue(Reference{declaration.keyword, declaration.name}, expr.location);
    } else {
        value = evaluateBlockField(declaration, fields[0], expr.location);
        next = 1;
    }
    for (; value && next < fields.size(); ++next) {
        value = fieldOf(*value, fields[next], expr.location);
    }
    if (value) {
        value->location = expr.location;
    }
    return value;
}

void ExpressionEvaluator::reportUnknownReference(const Expr& expr, const std::string& written,
                                                 const std::string& expectedTarget) {
    Diagnostic& diagnostic = addError(
        diagnostics_, "E0201", "unknown reference '@" + written + "'", expr.location,
        (expectedTarget.empty() ? "nothing" : "no " + expectedTarget) + " named '" + written + "'");
    // Names visible from this scope; those of the expected kind first.
    std::vector<std::string> preferred;
    std::vector<std::string> all;
    for (const Declaration& declaration : names_.declarations()) {
        if (declaration.name.compare(0, scope_.size(), scope_) != 0) {
            continue;
        }
        std::string local = declaration.name.substr(scope_.size());
        all.push_back(local);
        if (declaration.keyword == expectedTarget) {
            preferred.push_back(local);
        }
    }
    std::optional<std::string> match = closestMatch(written, preferred);
    if (!match) {
        match = closestMatch(written, all);
    }
    if (match) {
        diagnostic.help.push_back(names_.suggestion("@" + *match, scope_ + *match));
    }
}

std::optional<Value> ExpressionEvaluator::evaluateBlockField(Declaration& declaration,
                                                             const std::string& field,
                                                             const SourceLocation& location) {
    if (!declaration.schema || !declaration.block) {
        return std::nullopt;  // the block's own error speaks for it
    }
    const AttributeSchema* attributeSchema = declaration.schema->find(field);
    if (!attributeSchema) {
        reportUnknownBlockField(declaration, field, location);
        return std::nullopt;
    }
    // The attribute in force: the block's own `=`, unless --set replaces it.
    const AttributeNode* written = nullptr;
    std::string scope = declaration.scope;
    for (const AttributeNode& attribute : declaration.block->attributes) {
        if (attribute.name == field && attribute.op == AssignOp::Set) {
            written = &attribute;
        }
    }
    if (auto setFound = setPatches_.find(declaration.name); setFound != setPatches_.end()) {
        for (const Patch& patch : setFound->second) {
            if (patch.attribute->name == field) {
                written = patch.attribute;
                scope = patch.scope;
            }
        }
    }
    if (!written) {
        if (attributeSchema->defaultValue) {
            Value value = *attributeSchema->defaultValue;
            value.location = location;
            return value;
        }
        addError(diagnostics_, "E0210", "'" + declaration.name + "' has no '" + field + "'",
                 location, "'" + field + "' is not set and has no default");
        return std::nullopt;
    }
    const std::string key = declaration.name + "." + field;
    if (std::find(evaluatingFields_.begin(), evaluatingFields_.end(), key) !=
        evaluatingFields_.end()) {
        addError(diagnostics_, "E0302", "'@" + key + "' depends on itself", location,
                 "used while computing its own value");
        return std::nullopt;
    }
    evaluatingFields_.push_back(key);
    std::optional<Value> value =
        evaluate(*written->value, scope,
                 isReferenceLike(*attributeSchema) ? referenceTarget(*attributeSchema) : "");
    if (value) {
        value = values_.coerce(std::move(*value), *attributeSchema, "'" + field + "'");
    }
    evaluatingFields_.pop_back();
    return value;
}

void ExpressionEvaluator::reportUnknownBlockField(const Declaration& declaration,
                                                  const std::string& field,
                                                  const SourceLocation& location) {
    std::vector<std::string> valid;
    for (const AttributeSchema& candidate : declaration.schema->attributes) {
        valid.push_back(candidate.name);
    }
    Diagnostic& diagnostic =
        addError(diagnostics_, "E0210",
                 "unknown field '" + field + "' of '" + declaration.name + "'", location,
                 "'" + declaration.name + "' is " +
                     withArticle(describeBlock(*declaration.schema)) + " without '" + field + "'");
    if (auto match = closestMatch(field, valid)) {
        diagnostic.help.push_back("did you mean '" + *match + "'?");
    }
    diagnostic.help.push_back("fields are: " + join(valid));
}

std::optional<Value> ExpressionEvaluator::fieldOf(const Value& value, const std::string& field,
                                                  const SourceLocation& location) {
    if (const GeoPosition* geo = value.get<GeoPosition>()) {
        if (field == "latitude" || field == "lat") {
            return makeValue(Quantity{geo->latitude, Dimension::Angle}, location);
        }
        if (field == "longitude" || field == "lon") {
            return makeValue(Quantity{geo->longitude, Dimension::Angle}, location);
        }
        if (field == "height" && geo->height) {
            return makeValue(Quantity{*geo->height, Dimension::Length}, location);
        }
    } else if (const ValueObject* object = value.get<ValueObject>()) {
        for (const auto& [key, item] : *object) {
            if (key == field) {
                Value result = item;
                result.location = location;
                return result;
            }
        }
    }
    addError(diagnostics_, "E0210",
             "unknown field '" + field + "' of " + withArticle(value.typeName()), location,
             value.get<GeoPosition>() ? "geo positions have latitude, longitude and height"
                                      : "no field named '" + field + "'");
    return std::nullopt;
}

std::optional<Value> ExpressionEvaluator::evaluateUnary(const Expr& expr) {
    std::optional<Value> operand = evaluate(*expr.children[0], "");
    if (!operand) {
        return std::nullopt;
    }
    if (expr.op == '!') {
        const bool* flag = operand->get<bool>();
        if (!flag) {
            addError(diagnostics_, "E0402", "expected bool, found " + operand->typeName(),
                     expr.location, "'!' works on true and false only");
            return std::nullopt;
        }
        return makeValue(!*flag, expr.location);
    }
    const Quantity* quantity = operand->get<Quantity>();
    if (!quantity) {
        addError(diagnostics_, "E0401", "cannot negate " + withArticle(operand->typeName()),
                 expr.location, "only numbers and quantities have a sign");
        return std::nullopt;
    }
    Quantity result = *quantity;
    if (expr.op == '-') {
        result.value = -result.value;
    }
    return makeValue(result, expr.location);
}

std::optional<Value> ExpressionEvaluator::evaluateBinary(const Expr& expr) {
    std::optional<Value> left = evaluate(*expr.children[0], "");
    std::optional<Value> right = evaluate(*expr.children[1], "");
    if (!left || !right) {
        return std::nullopt;
    }
    switch (expr.op) {
        case '&':
        case '|':
            return evaluateLogical(expr, *left, *right);
        case 'e':
        case 'n':
            return evaluateEquality(expr, *left, *right);
        case '<':
        case '>':
        case 'l':
        case 'g':
            return evaluateOrder(expr, *left, *right);
        default:
            return evaluateArithmetic(expr, *left, *right);
    }
}

std::optional<Value> ExpressionEvaluator::evaluateLogical(const Expr& expr, const Value& left,
                                                          const Value& right) {
    const bool* a = left.get<bool>();
    const bool* b = right.get<bool>();
    if (!a || !b) {
        const Value& wrong = a ? right : left;
        addError(diagnostics_, "E0402", "expected bool, found " + wrong.typeName(), wrong.location,
                 std::string("'") + operatorText(expr.op) + "' works on true and false only");
        return std::nullopt;
    }
    return makeValue(expr.op == '&' ? (*a && *b) : (*a || *b), expr.location);
}

std::optional<Value> ExpressionEvaluator::evaluateEquality(const Expr& expr, const Value& left,
                                                           const Value& right) {
    const Quantity* a = left.get<Quantity>();
    const Quantity* b = right.get<Quantity>();
    bool comparable =
        left.data.index() == right.data.index() && (!a || a->dimension == b->dimension);
    if (!comparable) {
        addError(diagnostics_, "E0401",
                 "cannot compare " + left.typeName() + " and " + right.typeName(), expr.location,
                 "both sides must have the same type and unit");
        return std::nullopt;
    }
    bool equal = canonicalText(left) == canonicalText(right);
    return makeValue(expr.op == 'e' ? equal : !equal, expr.location);
}

std::optional<Value> ExpressionEvaluator::evaluateOrder(const Expr& expr, const Value& left,
                                                        const Value& right) {
    const Quantity* a = left.get<Quantity>();
    const Quantity* b = right.get<Quantity>();
    const std::string* sa = left.get<std::string>();
    const std::string* sb = right.get<std::string>();
    int order = 0;
    if (a && b && a->dimension == b->dimension) {
        order = a->value < b->value ? -1 : (a->value > b->value ? 1 : 0);
    } else if (sa && sb) {
        // Strings compare by bytes, which orders canonical dates and times correctly.
        order = sa->compare(*sb) < 0 ? -1 : (sa->compare(*sb) > 0 ? 1 : 0);
    } else {
        addError(diagnostics_, "E0401",
                 "cannot compare " + left.typeName() + " and " + right.typeName(), expr.location,
                 "both sides must be quantities of the same unit");
        return std::nullopt;
    }
    bool result = expr.op == '<'   ? order < 0
                  : expr.op == '>' ? order > 0
                  : expr.op == 'l' ? order <= 0
                                   : order >= 0;
    return makeValue(result, expr.location);
}

std::optional<Value> ExpressionEvaluator::evaluateArithmetic(const Expr& expr, const Value& left,
                                                             const Value& right) {
    const char* verb = expr.op == '+'   ? "add"
                       : expr.op == '-' ? "subtract"
                       : expr.op == '*' ? "multiply"
                       : expr.op == '%' ? "take the remainder of"
                                        : "divide";
    const char* joiner = expr.op == '/' ? " by " : " and ";
    const Quantity* a = left.get<Quantity>();
    const Quantity* b = right.get<Quantity>();
    auto incompatible = [&](const std::string& why) -> std::optional<Value> {
        addError(diagnostics_, "E0401",
                 std::string("cannot ") + verb + " " + left.typeName() + joiner + right.typeName(),
                 expr.location, why);
        return std::nullopt;
    };
    if (!a || !b) {
        return incompatible("arithmetic works on numbers and quantities only");
    }
    auto scalar = [](Dimension d) { return d == Dimension::None || d == Dimension::Ratio; };
    Quantity result;
    switch (expr.op) {
        case '+':
        case '-':
            if (a->dimension != b->dimension) {
                return incompatible("the units do not match");
            }
            result = {expr.op == '+' ? a->value + b->value : a->value - b->value, a->dimension};
            break;
        case '*':
            if (!scalar(a->dimension) && !scalar(b->dimension)) {
                return incompatible("only plain numbers and percentages scale a quantity");
            }
            // A percentage scales the other side; a plain number takes the other's unit.
            result = {a->value * b->value, a->dimension == Dimension::Ratio   ? b->dimension
                                           : b->dimension == Dimension::Ratio ? a->dimension
                                           : a->dimension == Dimension::None  ? b->dimension
                                                                              : a->dimension};
            break;
        default:
            if (b->value == 0.0) {
                addError(diagnostics_, "E0408", "division by zero", right.location, "this is zero");
                return std::nullopt;
            }
            if (expr.op == '%') {
                if (a->dimension != b->dimension && !scalar(b->dimension)) {
                    return incompatible("the units do not match");
                }
                result = {std::fmod(a->value, b->value), a->dimension};
            } else if (a->dimension == b->dimension) {
                result = {a->value / b->value, Dimension::None};
            } else if (scalar(b->dimension)) {
                result = {a->value / b->value, a->dimension};
            } else {
                return incompatible("the result would have a unit Sylva does not know");
            }
            break;
    }
    return makeValue(result, expr.location);
}

std::optional<Value> ExpressionEvaluator::evaluateCall(const Expr& expr) {
    if (!functions_.accepts(expr)) {
        return std::nullopt;
    }
    std::vector<Value> arguments;
    bool evaluated = true;
    for (const ExprPtr& child : expr.children) {
        std::optional<Value> argument = evaluate(*child, "");
        if (argument) {
            arguments.push_back(std::move(*argument));
        } else {
            evaluated = false;
        }
    }
    if (!evaluated) {
        return std::nullopt;
    }
    return functions_.apply(expr, std::move(arguments));
}

}  // namespace sylva::dsl
