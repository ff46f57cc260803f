#include "sylva/core/sources/raster/BandExpression.h"

#include <cctype>
#include <cmath>
#include <cstdlib>

namespace sylva {

// Recursive-descent parser emitting postfix code (the classic shunting of a
// precedence-climbing grammar into a stack machine).
class BandExpressionParser {
public:
    BandExpressionParser(std::string_view text, const BandExpression::Resolver& resolve)
        : text_(text), resolve_(resolve) {}

    Result<BandExpression> run() {
        skipSpace();
        if (position_ >= text_.size()) {
            return Error{"empty expression"};
        }
        parseOr();
        skipSpace();
        if (!error_ && position_ < text_.size()) {
            fail("unexpected '" + std::string(1, text_[position_]) + "'");
        }
        if (error_) {
            return *error_;
        }
        int depth = 0;
        for (const auto& instruction : result_.program_) {
            depth += effect(instruction.op);
            result_.maxStack_ = std::max(result_.maxStack_, depth);
        }
        return result_;
    }

private:
    using Op = BandExpression::Op;

    static int effect(Op op) {
        switch (op) {
            case Op::Number:
            case Op::Variable:
                return 1;
            case Op::Negate:
            case Op::Not:
            case Op::Abs:
            case Op::Sqrt:
                return 0;
            case Op::Clamp:
                return -2;
            default:
                return -1;
        }
    }

    void fail(const std::string& reason) {
        if (!error_) {
            error_ = Error{reason + " at column " + std::to_string(position_ + 1)};
        }
    }
    void emit(Op op, double number = 0.0, int slot = 0) {
        result_.program_.push_back({op, number, slot});
    }
    void skipSpace() {
        while (position_ < text_.size() &&
               std::isspace(static_cast<unsigned char>(text_[position_]))) {
            ++position_;
        }
    }
    bool accept(std::string_view token) {
        skipSpace();
        if (text_.substr(position_, token.size()) != token) {
            return false;
        }
        // Word operators must not be a prefix of a longer name.
        if (std::isalpha(static_cast<unsigned char>(token[0]))) {
            const std::size_t end = position_ + token.size();
            if (end < text_.size() &&
                (std::isalnum(static_cast<unsigned char>(text_[end])) || text_[end] == '_')) {
                return false;
            }
        }
        position_ += token.size();
        return true;
    }

    void parseOr() {
        parseAnd();
        while (!error_ && (accept("||") || accept("or"))) {
            parseAnd();
            emit(Op::Or);
        }
    }
    void parseAnd() {
        parseNot();
        while (!error_ && (accept("&&") || accept("and"))) {
            parseNot();
            emit(Op::And);
        }
    }
    void parseNot() {
        skipSpace();
        if (text_.substr(position_, 2) != "!=" && (accept("!") || accept("not"))) {
            parseNot();
            emit(Op::Not);
            return;
        }
        parseCompare();
    }
    void parseCompare() {
        parseSum();
        static const std::pair<std::string_view, Op> kOps[] = {
            {"<=", Op::LessEqual}, {">=", Op::GreaterEqual}, {"==", Op::Equal},
            {"!=", Op::NotEqual},  {"<", Op::Less},          {">", Op::Greater}};
        for (const auto& [token, op] : kOps) {
            if (!error_ && accept(token)) {
                parseSum();
                emit(op);
                return;
            }
        }
    }
    void parseSum() {
        parseProduct();
        while (!error_) {
            if (accept("+")) {
                parseProduct();
                emit(Op::Add);
            } else if (accept("-")) {
                parseProduct();
                emit(Op::Subtract);
            } else {
                break;
            }
        }
    }
    void parseProduct() {
        parseUnary();
        while (!error_) {
            if (accept("*")) {
                parseUnary();
                emit(Op::Multiply);
            } else if (accept("/")) {
                parseUnary();
                emit(Op::Divide);
            } else {
                break;
            }
        }
    }
    void parseUnary() {
        if (accept("-")) {
            parseUnary();
            emit(Op::Negate);
            return;
        }
        parsePrimary();
        if (!error_ && accept("^")) {
            parseUnary();
            emit(Op::Power);
        }
    }
    void parsePrimary() {
        if (++depth_ > 200) {
            fail("expression nested too deeply");
            return;
        }
        skipSpace();
        if (position_ >= text_.size()) {
            fail("unexpected end of expression");
            return;
        }
        const char c = text_[position_];
        if (c == '(') {
            ++position_;
            parseOr();
            if (!error_ && !accept(")")) {
                fail("expected ')'");
            }
        } else if (std::isdigit(static_cast<unsigned char>(c)) || c == '.') {
            const std::string rest(text_.substr(position_));
            char* end = nullptr;
            const double value = std::strtod(rest.c_str(), &end);
            if (end == rest.c_str()) {
                fail("bad number");
                return;
            }
            position_ += static_cast<std::size_t>(end - rest.c_str());
            emit(Op::Number, value);
        } else if (std::isalpha(static_cast<unsigned char>(c)) || c == '_') {
            const std::size_t start = position_;
            while (position_ < text_.size() &&
                   (std::isalnum(static_cast<unsigned char>(text_[position_])) ||
                    text_[position_] == '_' || text_[position_] == '.')) {
                ++position_;
            }
            const std::string name(text_.substr(start, position_ - start));
            skipSpace();
            if (position_ < text_.size() && text_[position_] == '(') {
                parseCall(name, start);
                return;
            }
            std::optional<int> slot = resolve_(name);
            if (!slot) {
                position_ = start;
                fail("unknown name '" + name + "'");
                return;
            }
            emit(Op::Variable, 0.0, *slot);
        } else {
            fail("unexpected '" + std::string(1, c) + "'");
        }
        --depth_;
    }
    void parseCall(const std::string& name, std::size_t start) {
        static const std::tuple<std::string_view, Op, int> kFunctions[] = {{"min", Op::Min, 2},
                                                                           {"max", Op::Max, 2},
                                                                           {"abs", Op::Abs, 1},
                                                                           {"sqrt", Op::Sqrt, 1},
                                                                           {"clamp", Op::Clamp, 3}};
        for (const auto& [function, op, arity] : kFunctions) {
            if (name != function) {
                continue;
            }
            ++position_;  // '('
            for (int i = 0; i < arity && !error_; ++i) {
                if (i > 0 && !accept(",")) {
                    fail(name + "() takes " + std::to_string(arity) + " arguments");
                    return;
                }
                parseOr();
            }
            if (!error_ && !accept(")")) {
                fail("expected ')' after the arguments of " + name + "()");
                return;
            }
            emit(op);
            --depth_;
            return;
        }
        position_ = start;
        fail("unknown function '" + name + "'");
    }

    std::string_view text_;
    const BandExpression::Resolver& resolve_;
    std::size_t position_ = 0;
    int depth_ = 0;
    std::optional<Error> error_;
    BandExpression result_;
};

Result<BandExpression> BandExpression::parse(std::string_view text, const Resolver& resolve) {
    return BandExpressionParser(text, resolve).run();
}

double BandExpression::evaluate(const double* variables) const {
    double stackStorage[64];
    std::vector<double> heap;
    double* stack = stackStorage;
    if (maxStack_ > 64) {
        heap.resize(static_cast<std::size_t>(maxStack_));
        stack = heap.data();
    }
    int top = 0;  // number of values on the stack
    auto truth = [](double v) { return v != 0.0 && !std::isnan(v); };
    for (const Instruction& in : program_) {
        switch (in.op) {
            case Op::Number:
                stack[top++] = in.number;
                continue;
            case Op::Variable:
                stack[top++] = variables[in.slot];
                continue;
            case Op::Negate:
                stack[top - 1] = -stack[top - 1];
                continue;
            case Op::Not:
                stack[top - 1] = truth(stack[top - 1]) ? 0.0 : 1.0;
                continue;
            case Op::Abs:
                stack[top - 1] = std::abs(stack[top - 1]);
                continue;
            case Op::Sqrt:
                stack[top - 1] = stack[top - 1] > 0 ? std::sqrt(stack[top - 1]) : 0.0;
                continue;
            case Op::Clamp: {
                const double x = stack[top - 3], lo = stack[top - 2], hi = stack[top - 1];
                top -= 2;
                stack[top - 1] = x < lo ? lo : (x > hi ? hi : x);
                continue;
            }
            default:
                break;
        }
        const double b = stack[--top];
        double& a = stack[top - 1];
        switch (in.op) {
            case Op::Add:
                a = a + b;
                break;
            case Op::Subtract:
                a = a - b;
                break;
            case Op::Multiply:
                a = a * b;
                break;
            case Op::Divide:
                a = b != 0.0 ? a / b : 0.0;
                break;
            case Op::Power:
                a = std::pow(a, b);
                break;
            case Op::Less:
                a = a < b;
                break;
            case Op::LessEqual:
                a = a <= b;
                break;
            case Op::Greater:
                a = a > b;
                break;
            case Op::GreaterEqual:
                a = a >= b;
                break;
            case Op::Equal:
                a = a == b;
                break;
            case Op::NotEqual:
                a = a != b;
                break;
            case Op::And:
                a = truth(a) && truth(b);
                break;
            case Op::Or:
                a = truth(a) || truth(b);
                break;
            case Op::Min:
                a = std::min(a, b);
                break;
            case Op::Max:
                a = std::max(a, b);
                break;
            default:
                break;
        }
    }
    return top > 0 ? stack[top - 1] : 0.0;
}

}  // namespace sylva
