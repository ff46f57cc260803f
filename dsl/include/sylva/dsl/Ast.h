// The syntax tree of a project file, every node with its source range. Produced by the
// Parser, consumed by the Resolver; no semantic checks happen here.
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "sylva/core/base/SourceLocation.h"
#include "sylva/core/model/Value.h"

namespace sylva::dsl {

struct Expr;
using ExprPtr = std::unique_ptr<Expr>;

struct Expr {
    enum class Kind {
        Number,
        String,
        Color,
        Bool,
        Reference,
        Word,
        List,
        Object,
        Call,
        Unary,
        Binary,
        DateTime,     // text holds the canonical ISO form
        Conditional,  // children: condition, then, else
        Index,        // children: container, index
        Field         // children: object; text: the field name
    };
    Kind kind = Kind::Number;
    SourceLocation location;  // the whole expression (one line at most for carets)

    double number = 0.0;  // Number: SI value
    Dimension dimension = Dimension::None;
    std::string text;   // String value, Word, Reference name, Call function name
    std::string field;  // Reference: part after '.', empty if none
    Color color;
    bool boolean = false;
    // Unary: '-', '+', '!'. Binary: '+', '-', '*', '/', '%', '<', '>', and for the two-
    // character operators: 'l' <=, 'g' >=, 'e' ==, 'n' !=, '&' &&, '|' ||.
    char op = 0;

    // List elements, Call arguments, Unary operand, Binary operands, Object values.
    std::vector<ExprPtr> children;
    // Object keys with their locations, parallel to children.
    std::vector<std::pair<std::string, SourceLocation>> keys;
};

enum class AssignOp { Set, Append, Remove };  // =, +=, -=

struct AttributeNode {
    std::string name;
    SourceLocation nameLocation;
    ExprPtr value;
    AssignOp op = AssignOp::Set;
    SourceLocation opLocation;
};

// `override @target { attributes }` or `override render { attributes }` inside a scenario.
struct OverrideNode {
    std::string target;  // the reference as written, without '@' ("forest", "ns.forest")
    SourceLocation targetLocation;
    bool render = false;  // `override render { ... }`: the render block (target "render")
    std::vector<AttributeNode> attributes;
};

// `keyword [name] [: kind] [extends parent] { attributes overrides }`
struct BlockNode {
    std::string keyword;
    SourceLocation keywordLocation;
    std::string name;  // empty when anonymous
    SourceLocation nameLocation;
    std::string kind;  // empty when not written
    SourceLocation kindLocation;
    std::vector<AttributeNode> attributes;
    std::string extends;  // empty when not written
    SourceLocation extendsLocation;
    std::vector<OverrideNode> overrides;
};

// `import "path" [as namespace]`
struct ImportNode {
    std::string path;
    SourceLocation pathLocation;
    std::string alias;  // empty: the imported names merge into the importing file
    SourceLocation aliasLocation;
};

// `param name [: type] [= default] ["doc"]`
struct ParamNode {
    std::string name;
    SourceLocation nameLocation;
    std::string type;  // empty when not written
    SourceLocation typeLocation;
    ExprPtr defaultValue;  // null when not written
    std::string doc;
};

using Statement = std::variant<BlockNode, ParamNode, ImportNode>;

struct FileNode {
    std::vector<Statement> statements;  // in source order
};

// A location covering `first` through `last` when both are on one line, else `first`.
SourceLocation spanLocations(const SourceLocation& first, const SourceLocation& last);

}  // namespace sylva::dsl
