// BandExpression: a small, safe arithmetic expression over texel values, for `mask`
// sources (e.g. NDVI "(nir - red) / (nir + red) > 0.35"). Parsed once by recursive
// descent into a postfix program evaluated on a value stack; it can only read the
// variables given to it, call a fixed set of pure functions and do arithmetic: no
// code is ever executed from the text.
//
// Grammar (lowest precedence first):
//   or      := and { ("||" | "or") and }
//   and     := not { ("&&" | "and") not }
//   not     := ("!" | "not") not | compare
//   compare := sum [ ("<" | "<=" | ">" | ">=" | "==" | "!=") sum ]
//   sum     := product { ("+" | "-") product }
//   product := unary { ("*" | "/") unary }
//   unary   := "-" unary | power
//   power   := primary [ "^" unary ]
//   primary := number | name | function "(" or { "," or } ")" | "(" or ")"
// Names are letters, digits, '_' and '.', starting with a letter or '_'. Functions:
// min(a, b), max(a, b), abs(x), sqrt(x), clamp(x, lo, hi). Comparisons and logic give
// 1 or 0 (non-zero is true). Division by zero gives 0; sqrt of a negative gives 0.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "sylva/core/base/Result.h"

namespace sylva {

class BandExpression {
public:
    // Maps a variable name to its slot in the array given to evaluate(), or nullopt
    // for an unknown name.
    using Resolver = std::function<std::optional<int>(std::string_view name)>;

    // Errors: "<reason> at column <n>" (1-based), e.g. "unknown name 'nir' at column 2".
    static Result<BandExpression> parse(std::string_view text, const Resolver& resolve);

    double evaluate(const double* variables) const;

private:
    enum class Op {
        Number,
        Variable,
        Negate,
        Add,
        Subtract,
        Multiply,
        Divide,
        Power,
        Less,
        LessEqual,
        Greater,
        GreaterEqual,
        Equal,
        NotEqual,
        And,
        Or,
        Not,
        Min,
        Max,
        Abs,
        Sqrt,
        Clamp
    };
    struct Instruction {
        Op op;
        double number = 0.0;
        int slot = 0;
    };
    std::vector<Instruction> program_;
    int maxStack_ = 0;

    friend class BandExpressionParser;
};

}  // namespace sylva
