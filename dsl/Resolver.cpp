#include "sylva/dsl/Resolver.h"

#include <algorithm>
#include <cstdio>
#include <functional>
#include <numbers>
#include <set>
#include <utility>

#include "sylva/dsl/EditDistance.h"

namespace sylva::dsl {

namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

std::string formatNumber(double value) {
    char buffer[40];
    std::snprintf(buffer, sizeof buffer, "%.6g", value);
    return buffer;
}

std::string join(const std::vector<std::string>& items) {
    std::string out;
    for (const std::string& item : items) {
        out += (out.empty() ? "" : ", ") + item;
    }
    return out;
}

std::string withArticle(const std::string& noun) {
    bool vowel = !noun.empty() && std::string_view("aeiou").find(noun[0]) != std::string::npos;
    return (vowel ? "an " : "a ") + noun;
}

template <typename T>
Value makeValue(T data, const SourceLocation& location) {
    Value value;
    value.data = std::move(data);
    value.location = location;
    return value;
}

std::string referenceTarget(const AttributeSchema& schema) {
    return schema.target.empty() ? std::string("source") : schema.target;
}

std::string expectedName(const AttributeSchema& schema) {
    switch (schema.type) {
        case ValueType::Number:
            return dimensionName(schema.dimension);
        case ValueType::Bool:
            return "bool";
        case ValueType::String:
            return "string";
        case ValueType::Color:
            return "colour";
        case ValueType::Geo:
            return "geo position";
        case ValueType::Word:
            return "one of: " + join(schema.words);
        case ValueType::Reference:
            return schema.port != PortType::None
                       ? std::string(portTypeName(schema.port)) + " source"
                       : referenceTarget(schema);
        case ValueType::List:
            return "list";
        case ValueType::Object:
            return "object";
    }
    return "value";
}

// The unit a bare number is read in, per dimension, and its scale to SI.
struct AssumedUnit {
    const char* name;
    double scale;
};
AssumedUnit assumedUnit(Dimension dimension) {
    switch (dimension) {
        case Dimension::Length:
            return {"metres", 1.0};
        case Dimension::Angle:
            return {"degrees", kDegree};
        case Dimension::Time:
            return {"seconds", 1.0};
        case Dimension::Ratio:
            return {"a fraction", 1.0};
        case Dimension::Pixels:
            return {"pixels", 1.0};
        case Dimension::None:
            break;
    }
    return {"", 1.0};
}

const std::vector<std::string> kParamTypes = {"number",     "length", "angle", "time",
                                              "percentage", "string", "bool",  "colour"};

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

bool isAnonymousKeyword(const std::string& keyword) {
    return keyword == "project" || keyword == "render";
}

}  // namespace

std::string formatQuantity(const Quantity& quantity) {
    switch (quantity.dimension) {
        case Dimension::None:
            return formatNumber(quantity.value);
        case Dimension::Length:
            return formatNumber(quantity.value) + "m";
        case Dimension::Angle:
            return formatNumber(quantity.value / kDegree) + "deg";
        case Dimension::Time:
            return formatNumber(quantity.value) + "s";
        case Dimension::Ratio:
            return formatNumber(quantity.value * 100.0) + "%";
        case Dimension::Pixels:
            return formatNumber(quantity.value) + "px";
    }
    return formatNumber(quantity.value);
}

Resolver::Resolver(const SchemaRegistry& schema, std::vector<Diagnostic>& diagnostics)
    : schema_(schema), diagnostics_(diagnostics) {}

std::optional<ProjectModel> Resolver::resolve(const FileNode& file,
                                              const std::vector<DefineNode>& defines,
                                              const std::filesystem::path& path) {
    declarations_.reserve(file.statements.size());
    for (const Statement& statement : file.statements) {
        declare(statement);
    }
    applyDefines(defines);
    for (Declaration& declaration : declarations_) {
        if (declaration.keyword == "param") {
            evaluateParam(declaration, declaration.location);
        }
    }

    ProjectModel model;
    model.file = path;
    for (const auto& [node, kindSchema] : blocks_) {
        std::optional<Block> block = checkBlock(*node, *kindSchema);
        if (!block) {
            continue;
        }
        if (block->keyword == "source") {
            model.sources.push_back(std::move(*block));
        } else if (block->keyword == "camera") {
            model.cameras.push_back(std::move(*block));
        } else if (block->keyword == "scenario") {
            model.scenarios.push_back(std::move(*block));
        } else if (block->keyword == "views") {
            model.views.push_back(std::move(*block));
        } else if (block->keyword == "project") {
            model.project = std::move(*block);
        } else if (block->keyword == "render") {
            model.render = std::move(*block);
        }
    }
    // project and render exist even when the file omits them.
    for (Block* block : {&model.project, &model.render}) {
        if (block->keyword.empty()) {
            block->keyword = block == &model.project ? "project" : "render";
            block->location.file = std::make_shared<const std::string>(path.string());
            if (const KindSchema* kindSchema = schema_.find(block->keyword)) {
                fillDefaults(*block, *kindSchema);
            }
        }
    }
    findCycles(model.sources);

    for (const Declaration& declaration : declarations_) {
        if (declaration.keyword != "param") {
            continue;
        }
        if (!declaration.used) {
            addWarning(diagnostics_, "W0201", "unused param '" + declaration.name + "'",
                       declaration.location, "declared here but never used");
        }
        if (!declaration.value) {
            continue;
        }
        Block param;
        param.keyword = "param";
        param.name = declaration.name;
        param.kind = declaration.param->type;
        param.location = declaration.location;
        param.attributes.push_back({"value", *declaration.value, declaration.location});
        if (!declaration.param->doc.empty()) {
            param.attributes.push_back({"doc",
                                        makeValue(declaration.param->doc, declaration.location),
                                        declaration.location});
        }
        model.params.push_back(std::move(param));
    }
    if (!model.scenarios.empty()) {
        model.scenario = model.scenarios.front().name;
    }
    if (hasErrors(diagnostics_)) {
        return std::nullopt;
    }
    return model;
}

bool Resolver::addName(Declaration declaration) {
    auto found = names_.find(declaration.name);
    if (found != names_.end()) {
        const Declaration& first = declarations_[found->second];
        addError(diagnostics_, "E0202", "duplicate name '" + declaration.name + "'",
                 declaration.location, "'" + declaration.name + "' is already defined")
            .notes.push_back({"'" + declaration.name + "' first defined here", first.location});
        return false;
    }
    names_.emplace(declaration.name, declarations_.size());
    declarations_.push_back(std::move(declaration));
    return true;
}

void Resolver::declare(const Statement& statement) {
    if (const auto* param = std::get_if<ParamNode>(&statement)) {
        Declaration declaration;
        declaration.keyword = "param";
        declaration.name = param->name;
        declaration.location = param->nameLocation;
        declaration.param = param;
        declaration.valueExpr = param->defaultValue.get();
        addName(std::move(declaration));
        return;
    }
    const auto& block = std::get<BlockNode>(statement);
    std::vector<std::string> keywords;
    for (const KindSchema& kindSchema : schema_.all()) {
        if (std::find(keywords.begin(), keywords.end(), kindSchema.keyword) == keywords.end()) {
            keywords.push_back(kindSchema.keyword);
        }
    }
    if (std::find(keywords.begin(), keywords.end(), block.keyword) == keywords.end()) {
        Diagnostic& diagnostic =
            addError(diagnostics_, "E0203", "unknown block keyword '" + block.keyword + "'",
                     block.keywordLocation, "not a block keyword");
        if (auto match = closestMatch(block.keyword, keywords)) {
            diagnostic.help.push_back("did you mean '" + *match + "'?");
        }
        diagnostic.help.push_back("block keywords are: param, " + join(keywords));
        return;
    }
    const std::string& keyword = block.keyword;
    const KindSchema* kindSchema = nullptr;
    if (keyword == "source") {
        if (block.name.empty()) {
            addError(diagnostics_, "E0205", "source needs a name and a kind", block.keywordLocation,
                     "write 'source NAME : KIND { ... }'");
            return;
        }
        if (block.kind.empty()) {
            addError(diagnostics_, "E0205", "source '" + block.name + "' needs a kind",
                     block.nameLocation, "write 'source " + block.name + " : KIND { ... }'");
        } else {
            kindSchema = schema_.find("source", block.kind);
            if (!kindSchema) {
                std::vector<std::string> kinds = schema_.sourceKinds();
                Diagnostic& diagnostic =
                    addError(diagnostics_, "E0204", "unknown source kind '" + block.kind + "'",
                             block.kindLocation, "not a source kind");
                if (auto match = closestMatch(block.kind, kinds)) {
                    diagnostic.help.push_back("did you mean '" + *match + "'?");
                }
                diagnostic.help.push_back("source kinds are: " + join(kinds));
            }
        }
    } else {
        kindSchema = schema_.find(keyword);
        if (!block.kind.empty()) {
            addError(diagnostics_, "E0205", "'" + keyword + "' blocks have no kind",
                     block.kindLocation, "only sources have a kind");
            return;
        }
        if (isAnonymousKeyword(keyword)) {
            if (!block.name.empty()) {
                addError(diagnostics_, "E0205", "'" + keyword + "' block takes no name",
                         block.nameLocation, "remove this name");
                return;
            }
            const BlockNode*& first = keyword == "project" ? project_ : render_;
            if (first) {
                addError(diagnostics_, "E0206", "duplicate '" + keyword + "' block",
                         block.keywordLocation, "second '" + keyword + "' block")
                    .notes.push_back(
                        {"first '" + keyword + "' block here", first->keywordLocation});
                return;
            }
            first = &block;
            blocks_.emplace_back(&block, kindSchema);
            return;
        }
        if (block.name.empty()) {
            addError(diagnostics_, "E0205", "'" + keyword + "' block needs a name",
                     block.keywordLocation, "write '" + keyword + " NAME { ... }'");
            return;
        }
    }
    Declaration declaration;
    declaration.keyword = keyword;
    declaration.name = block.name;
    declaration.kind = block.kind;
    declaration.location = block.nameLocation;
    declaration.block = &block;
    declaration.schema = kindSchema;
    if (addName(std::move(declaration)) && kindSchema) {
        blocks_.emplace_back(&block, kindSchema);
    }
}

void Resolver::applyDefines(const std::vector<DefineNode>& defines) {
    for (const DefineNode& define : defines) {
        auto found = names_.find(define.name);
        if (found == names_.end() || declarations_[found->second].keyword != "param") {
            Diagnostic& diagnostic =
                addError(diagnostics_, "E0207", "undeclared param '" + define.name + "'",
                         define.nameLocation, "no param named '" + define.name + "'");
            std::vector<std::string> params;
            for (const Declaration& declaration : declarations_) {
                if (declaration.keyword == "param") {
                    params.push_back(declaration.name);
                }
            }
            if (auto match = closestMatch(define.name, params)) {
                diagnostic.help.push_back("did you mean '" + *match + "' (defined at " +
                                          shortLocation(declarations_[names_[*match]].location) +
                                          ")?");
            }
            diagnostic.help.push_back("-D sets only params declared with 'param'");
            continue;
        }
        if (define.value) {
            declarations_[found->second].valueExpr = define.value.get();
        } else {
            // The value did not parse (already reported); keep the param quiet.
            declarations_[found->second].valueExpr = nullptr;
            declarations_[found->second].state = 2;
        }
    }
}

std::optional<Value> Resolver::evaluateParam(Declaration& param, const SourceLocation& use) {
    if (param.state == 2) {
        return param.value;
    }
    if (param.state == 1) {
        addError(diagnostics_, "E0302", "param '" + param.name + "' depends on itself", use,
                 "used while computing its own value");
        return std::nullopt;
    }
    param.state = 1;
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
        value = evaluate(*param.valueExpr, "");
        if (value && typed) {
            value = coerce(std::move(*value), typeSchema, "param '" + param.name + "'");
        }
    }
    param.state = 2;
    param.value = value;
    return value;
}

std::string Resolver::describeBlock(const KindSchema& kindSchema) const {
    return kindSchema.keyword == "source" ? kindSchema.kind + " source" : kindSchema.keyword;
}

std::optional<Block> Resolver::checkBlock(const BlockNode& node, const KindSchema& kindSchema) {
    Block block;
    block.keyword = node.keyword;
    block.name = node.name;
    block.kind = node.kind;
    block.location = node.name.empty() ? node.keywordLocation : node.nameLocation;
    std::vector<const AttributeNode*> seen;
    for (const AttributeNode& attribute : node.attributes) {
        auto first = std::find_if(seen.begin(), seen.end(), [&](const AttributeNode* other) {
            return other->name == attribute.name;
        });
        if (first != seen.end()) {
            addError(diagnostics_, "E0209", "duplicate attribute '" + attribute.name + "'",
                     attribute.nameLocation,
                     "'" + attribute.name + "' is already set in this block")
                .notes.push_back({"first set here", (*first)->nameLocation});
            continue;
        }
        seen.push_back(&attribute);
        const AttributeSchema* attributeSchema = kindSchema.find(attribute.name);
        if (!attributeSchema) {
            std::vector<std::string> valid;
            for (const AttributeSchema& candidate : kindSchema.attributes) {
                valid.push_back(candidate.name);
            }
            Diagnostic& diagnostic = addError(
                diagnostics_, "E0208", "unknown attribute '" + attribute.name + "'",
                attribute.nameLocation, "not an attribute of " + describeBlock(kindSchema));
            if (auto match = closestMatch(attribute.name, valid)) {
                diagnostic.help.push_back("did you mean '" + *match + "'?");
            }
            diagnostic.help.push_back("valid attributes: " + join(valid));
            continue;
        }
        bool referenceLike = attributeSchema->type == ValueType::Reference ||
                             (attributeSchema->type == ValueType::List &&
                              attributeSchema->element == ValueType::Reference);
        std::optional<Value> value =
            evaluate(*attribute.value, referenceLike ? referenceTarget(*attributeSchema) : "");
        if (!value) {
            continue;
        }
        value = coerce(std::move(*value), *attributeSchema, "'" + attribute.name + "'");
        if (!value) {
            continue;
        }
        block.attributes.push_back({attribute.name, std::move(*value), attribute.nameLocation});
    }
    for (const AttributeSchema& attributeSchema : kindSchema.attributes) {
        bool written = std::any_of(seen.begin(), seen.end(), [&](const AttributeNode* attribute) {
            return attribute->name == attributeSchema.name;
        });
        if (attributeSchema.required && !written) {
            std::string what = describeBlock(kindSchema);
            if (!node.name.empty()) {
                what += " '" + node.name + "'";
            }
            addError(diagnostics_, "E0405",
                     "missing required attribute '" + attributeSchema.name + "'", block.location,
                     what + " needs '" + attributeSchema.name + "'")
                .help.push_back(attributeSchema.name + ": " + attributeSchema.doc);
        }
    }
    std::vector<std::string> written;
    for (const AttributeNode* attribute : seen) {
        written.push_back(attribute->name);
    }
    // An attribute written with an error gets no default: the error already speaks for it.
    fillDefaults(block, kindSchema, written);
    return block;
}

void Resolver::fillDefaults(Block& block, const KindSchema& kindSchema,
                            const std::vector<std::string>& written) {
    for (const AttributeSchema& attributeSchema : kindSchema.attributes) {
        if (!attributeSchema.defaultValue || block.find(attributeSchema.name) ||
            std::find(written.begin(), written.end(), attributeSchema.name) != written.end()) {
            continue;
        }
        Value value = *attributeSchema.defaultValue;
        value.location = block.location;
        block.attributes.push_back({attributeSchema.name, std::move(value), block.location});
    }
}

std::optional<Value> Resolver::evaluate(const Expr& expr, const std::string& expectedTarget) {
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
        case Expr::Kind::Reference:
            return evaluateReference(expr, expectedTarget);
        case Expr::Kind::Unary:
            return evaluateUnary(expr);
        case Expr::Kind::Binary:
            return evaluateBinary(expr);
        case Expr::Kind::Call:
            return evaluateCall(expr);
        case Expr::Kind::List: {
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
            return ok ? std::optional<Value>(makeValue(std::move(list), expr.location))
                      : std::nullopt;
        }
        case Expr::Kind::Object: {
            ValueObject object;
            bool ok = true;
            for (std::size_t i = 0; i < expr.children.size(); ++i) {
                const auto& [key, keyLocation] = expr.keys[i];
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
            return ok ? std::optional<Value>(makeValue(std::move(object), expr.location))
                      : std::nullopt;
        }
    }
    return std::nullopt;
}

std::optional<Value> Resolver::evaluateReference(const Expr& expr,
                                                 const std::string& expectedTarget) {
    auto found = names_.find(expr.text);
    if (found == names_.end()) {
        Diagnostic& diagnostic =
            addError(diagnostics_, "E0201", "unknown reference '@" + expr.text + "'", expr.location,
                     (expectedTarget.empty() ? "nothing" : "no " + expectedTarget) + " named '" +
                         expr.text + "'");
        std::vector<std::string> preferred;
        std::vector<std::string> all;
        for (const Declaration& declaration : declarations_) {
            all.push_back(declaration.name);
            if (declaration.keyword == expectedTarget) {
                preferred.push_back(declaration.name);
            }
        }
        std::optional<std::string> match = closestMatch(expr.text, preferred);
        if (!match) {
            match = closestMatch(expr.text, all);
        }
        if (match) {
            diagnostic.help.push_back("did you mean '@" + *match + "' (defined at " +
                                      shortLocation(declarations_[names_[*match]].location) + ")?");
        }
        return std::nullopt;
    }
    Declaration& declaration = declarations_[found->second];
    if (!expr.field.empty()) {
        addError(diagnostics_, "E0210",
                 "field access '@" + expr.text + "." + expr.field + "' is not supported yet",
                 expr.location, "write '@" + expr.text + "' or the value itself");
        return std::nullopt;
    }
    if (declaration.keyword == "param") {
        declaration.used = true;
        std::optional<Value> value = evaluateParam(declaration, expr.location);
        if (value) {
            value->location = expr.location;
        }
        return value;
    }
    return makeValue(Reference{declaration.keyword, declaration.name}, expr.location);
}

std::optional<Value> Resolver::evaluateUnary(const Expr& expr) {
    std::optional<Value> operand = evaluate(*expr.children[0], "");
    if (!operand) {
        return std::nullopt;
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

std::optional<Value> Resolver::evaluateBinary(const Expr& expr) {
    std::optional<Value> left = evaluate(*expr.children[0], "");
    std::optional<Value> right = evaluate(*expr.children[1], "");
    if (!left || !right) {
        return std::nullopt;
    }
    const char* verb = expr.op == '+'   ? "add"
                       : expr.op == '-' ? "subtract"
                       : expr.op == '*' ? "multiply"
                                        : "divide";
    const char* joiner = expr.op == '/' ? " by " : " and ";
    const Quantity* a = left->get<Quantity>();
    const Quantity* b = right->get<Quantity>();
    auto incompatible = [&](const std::string& why) -> std::optional<Value> {
        addError(
            diagnostics_, "E0401",
            std::string("cannot ") + verb + " " + left->typeName() + joiner + right->typeName(),
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
                addError(diagnostics_, "E0408", "division by zero", right->location,
                         "this is zero");
                return std::nullopt;
            }
            if (a->dimension == b->dimension) {
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

std::optional<double> Resolver::coerceAngle(const Value& value, const std::string& what) {
    const Quantity* quantity = value.get<Quantity>();
    if (!quantity) {
        addError(diagnostics_, "E0402", "expected angle, found " + value.typeName(), value.location,
                 what + " must be an angle");
        return std::nullopt;
    }
    if (quantity->dimension == Dimension::None) {
        Quantity read{quantity->value * kDegree, Dimension::Angle};
        addWarning(diagnostics_, "W0101",
                   "bare number where an angle is expected; assuming degrees", value.location,
                   "read as " + formatQuantity(read));
        return read.value;
    }
    if (quantity->dimension != Dimension::Angle) {
        addError(diagnostics_, "E0403",
                 std::string("expected angle, found ") + dimensionName(quantity->dimension),
                 value.location, what + " must be an angle");
        return std::nullopt;
    }
    return quantity->value;
}

std::optional<Value> Resolver::evaluateCall(const Expr& expr) {
    if (expr.text != "geo") {
        Diagnostic& diagnostic =
            addError(diagnostics_, "E0211", "unknown function '" + expr.text + "'", expr.location,
                     "not a function");
        if (auto match = closestMatch(expr.text, {"geo"})) {
            diagnostic.help.push_back("did you mean '" + *match + "'?");
        }
        diagnostic.help.push_back("functions are: geo");
        return std::nullopt;
    }
    if (expr.children.size() < 2 || expr.children.size() > 3) {
        addError(diagnostics_, "E0407",
                 "geo() takes 2 or 3 arguments, found " + std::to_string(expr.children.size()),
                 expr.location, "write geo(latitude, longitude[, height])");
        return std::nullopt;
    }
    std::vector<Value> arguments;
    for (const ExprPtr& child : expr.children) {
        std::optional<Value> argument = evaluate(*child, "");
        if (!argument) {
            return std::nullopt;
        }
        arguments.push_back(std::move(*argument));
    }
    std::optional<double> latitude = coerceAngle(arguments[0], "latitude");
    std::optional<double> longitude = coerceAngle(arguments[1], "longitude");
    bool ok = latitude && longitude;
    auto checkRange = [&](std::optional<double> angle, double limit, const char* what,
                          const Value& where) {
        if (angle && (*angle < -limit * kDegree || *angle > limit * kDegree)) {
            addError(diagnostics_, "E0404", std::string(what) + " out of range", where.location,
                     formatQuantity({*angle, Dimension::Angle}) + " is outside [-" +
                         formatNumber(limit) + "deg, " + formatNumber(limit) + "deg]");
            ok = false;
        }
    };
    checkRange(latitude, 90.0, "latitude", arguments[0]);
    checkRange(longitude, 180.0, "longitude", arguments[1]);
    GeoPosition position;
    if (arguments.size() == 3) {
        AttributeSchema heightSchema;
        heightSchema.type = ValueType::Number;
        heightSchema.dimension = Dimension::Length;
        std::optional<Value> height = coerce(arguments[2], heightSchema, "height");
        if (!height) {
            return std::nullopt;
        }
        position.height = height->get<Quantity>()->value;
    }
    if (!ok) {
        return std::nullopt;
    }
    position.latitude = *latitude;
    position.longitude = *longitude;
    return makeValue(position, expr.location);
}

std::optional<Value> Resolver::coerce(Value value, const AttributeSchema& schema,
                                      const std::string& what) {
    auto wrongType = [&]() -> std::optional<Value> {
        addError(diagnostics_, "E0402",
                 "expected " + expectedName(schema) + ", found " + value.typeName(), value.location,
                 what + " must be " + withArticle(expectedName(schema)));
        return std::nullopt;
    };
    switch (schema.type) {
        case ValueType::Number: {
            Quantity* quantity = std::get_if<Quantity>(&value.data);
            if (!quantity) {
                return wrongType();
            }
            if (quantity->dimension != schema.dimension) {
                if (quantity->dimension != Dimension::None) {
                    addError(diagnostics_, "E0403",
                             std::string("expected ") + dimensionName(schema.dimension) +
                                 ", found " + dimensionName(quantity->dimension),
                             value.location,
                             what + " must be " + withArticle(dimensionName(schema.dimension)));
                    return std::nullopt;
                }
                AssumedUnit unit = assumedUnit(schema.dimension);
                quantity->value *= unit.scale;
                quantity->dimension = schema.dimension;
                addWarning(diagnostics_, "W0101",
                           std::string("bare number where ") +
                               withArticle(schema.dimension == Dimension::Pixels
                                               ? "pixel count"
                                               : dimensionName(schema.dimension)) +
                               " is expected; assuming " + unit.name,
                           value.location, "read as " + formatQuantity(*quantity));
            }
            if (schema.minimum && quantity->value < *schema.minimum) {
                addError(diagnostics_, "E0404", "value out of range for " + what, value.location,
                         formatQuantity(*quantity) + " is below the minimum " +
                             formatQuantity({*schema.minimum, schema.dimension}));
                return std::nullopt;
            }
            if (schema.maximum && quantity->value > *schema.maximum) {
                addError(diagnostics_, "E0404", "value out of range for " + what, value.location,
                         formatQuantity(*quantity) + " is above the maximum " +
                             formatQuantity({*schema.maximum, schema.dimension}));
                return std::nullopt;
            }
            return value;
        }
        case ValueType::Bool:
            return value.get<bool>() ? std::optional<Value>(std::move(value)) : wrongType();
        case ValueType::String:
            return value.get<std::string>() ? std::optional<Value>(std::move(value)) : wrongType();
        case ValueType::Color:
            return value.get<Color>() ? std::optional<Value>(std::move(value)) : wrongType();
        case ValueType::Geo:
            return value.get<GeoPosition>() ? std::optional<Value>(std::move(value)) : wrongType();
        case ValueType::Object:
            return value.get<ValueObject>() ? std::optional<Value>(std::move(value)) : wrongType();
        case ValueType::Word: {
            const Word* word = value.get<Word>();
            if (!word) {
                return wrongType();
            }
            if (!schema.words.empty() && std::find(schema.words.begin(), schema.words.end(),
                                                   word->text) == schema.words.end()) {
                Diagnostic& diagnostic =
                    addError(diagnostics_, "E0410", "unknown word '" + word->text + "' for " + what,
                             value.location, "expected one of: " + join(schema.words));
                if (auto match = closestMatch(word->text, schema.words)) {
                    diagnostic.help.push_back("did you mean '" + *match + "'?");
                }
                return std::nullopt;
            }
            return value;
        }
        case ValueType::Reference: {
            const Reference* reference = value.get<Reference>();
            std::string target = referenceTarget(schema);
            if (!reference) {
                addError(
                    diagnostics_, "E0402",
                    "expected " + expectedName(schema) + " reference, found " + value.typeName(),
                    value.location, what + " must be a reference like '@name'");
                return std::nullopt;
            }
            if (reference->kind != target) {
                addError(diagnostics_, "E0406", "expected " + target + ", found " + reference->kind,
                         value.location,
                         "'" + reference->name + "' is " + withArticle(reference->kind));
                return std::nullopt;
            }
            if (target == "source" && schema.port != PortType::None) {
                const Declaration& declaration = declarations_[names_[reference->name]];
                if (declaration.schema && declaration.schema->output != schema.port) {
                    addError(diagnostics_, "E0406",
                             std::string("expected ") + portTypeName(schema.port) + ", found " +
                                 portTypeName(declaration.schema->output),
                             value.location,
                             "'" + reference->name + "' is " + withArticle(declaration.kind) +
                                 " source, which outputs " +
                                 portTypeName(declaration.schema->output));
                    return std::nullopt;
                }
            }
            return value;
        }
        case ValueType::List: {
            ValueList* list = std::get_if<ValueList>(&value.data);
            if (!list) {
                return wrongType();
            }
            AttributeSchema element;
            element.type = schema.element;
            element.dimension = schema.dimension;
            element.port = schema.port;
            element.target = schema.target;
            element.minimum = schema.minimum;
            element.maximum = schema.maximum;
            bool ok = true;
            for (Value& item : *list) {
                // A list of records (a hypsometric ramp) cannot be described by `element`;
                // its consumer checks the records.
                if (schema.element == ValueType::Number && schema.dimension == Dimension::None &&
                    item.get<ValueObject>()) {
                    continue;
                }
                std::optional<Value> checked = coerce(std::move(item), element, what);
                if (checked) {
                    item = std::move(*checked);
                } else {
                    ok = false;
                }
            }
            return ok ? std::optional<Value>(std::move(value)) : std::nullopt;
        }
    }
    return std::nullopt;
}

void Resolver::findCycles(const std::vector<Block>& sources) {
    struct Edge {
        std::string from;
        std::string to;
        SourceLocation location;
    };
    std::map<std::string, std::vector<Edge>> graph;
    std::map<std::string, std::size_t> order;
    for (const Block& source : sources) {
        order.emplace(source.name, order.size());
        std::function<void(const Value&)> collect = [&](const Value& value) {
            if (const Reference* reference = value.get<Reference>()) {
                if (reference->kind == "source") {
                    graph[source.name].push_back({source.name, reference->name, value.location});
                }
            } else if (const ValueList* list = value.get<ValueList>()) {
                for (const Value& item : *list) {
                    collect(item);
                }
            } else if (const ValueObject* object = value.get<ValueObject>()) {
                for (const auto& entry : *object) {
                    collect(entry.second);
                }
            }
        };
        for (const Attribute& attribute : source.attributes) {
            collect(attribute.value);
        }
    }
    std::map<std::string, int> colour;
    std::vector<Edge> path;
    std::set<std::string> reported;
    std::function<void(const std::string&)> visit = [&](const std::string& node) {
        colour[node] = 1;
        for (const Edge& edge : graph[node]) {
            if (colour[edge.to] == 1) {
                // The cycle runs from where the path first left edge.to back to it.
                std::vector<Edge> cycle;
                for (std::size_t i = 0; i < path.size(); ++i) {
                    if (path[i].from == edge.to) {
                        cycle.assign(path.begin() + static_cast<std::ptrdiff_t>(i), path.end());
                        break;
                    }
                }
                cycle.push_back(edge);
                // Start at the source declared first, so the report is stable.
                auto first = std::min_element(
                    cycle.begin(), cycle.end(),
                    [&](const Edge& x, const Edge& y) { return order[x.from] < order[y.from]; });
                std::rotate(cycle.begin(), first, cycle.end());
                std::string chain = cycle.front().from;
                for (const Edge& step : cycle) {
                    chain += " -> " + step.to;
                }
                if (!reported.insert(chain).second) {
                    continue;
                }
                Diagnostic& diagnostic =
                    addError(diagnostics_, "E0301", "dependency cycle between sources",
                             cycle.front().location,
                             "'" + cycle.front().from + "' uses '" + cycle.front().to + "' here");
                for (std::size_t i = 1; i < cycle.size(); ++i) {
                    diagnostic.notes.push_back(
                        {"'" + cycle[i].from + "' uses '" + cycle[i].to + "'", cycle[i].location});
                }
                diagnostic.help.push_back("cycle: " + chain);
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

}  // namespace sylva::dsl
