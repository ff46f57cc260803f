#include "sylva/dsl/Parser.h"

#include <utility>

namespace sylva::dsl {

namespace {

bool isOpener(TokenKind kind) {
    return kind == TokenKind::LBrace || kind == TokenKind::LBracket || kind == TokenKind::LParen;
}
bool isCloser(TokenKind kind) {
    return kind == TokenKind::RBrace || kind == TokenKind::RBracket || kind == TokenKind::RParen;
}

ExprPtr makeExpr(Expr::Kind kind, const SourceLocation& location) {
    auto expr = std::make_unique<Expr>();
    expr->kind = kind;
    expr->location = location;
    return expr;
}

// Binding powers of the infix operators (higher binds tighter) and their Expr::op; the
// conditional's '?' binds loosest.
struct BinaryOperator {
    TokenKind kind;
    int power;
    char op;
};

constexpr BinaryOperator kBinaryOperators[] = {
    {TokenKind::Question, 1, 0},       {TokenKind::OrOr, 2, '|'},
    {TokenKind::AndAnd, 3, '&'},       {TokenKind::EqualEqual, 4, 'e'},
    {TokenKind::BangEqual, 4, 'n'},    {TokenKind::Less, 5, '<'},
    {TokenKind::LessEqual, 5, 'l'},    {TokenKind::Greater, 5, '>'},
    {TokenKind::GreaterEqual, 5, 'g'}, {TokenKind::Plus, 10, '+'},
    {TokenKind::Minus, 10, '-'},       {TokenKind::Star, 20, '*'},
    {TokenKind::Slash, 20, '/'},       {TokenKind::Percent, 20, '%'},
};

// The infix operator `kind` is, or nullptr.
const BinaryOperator* binaryOperator(TokenKind kind) {
    for (const BinaryOperator& binary : kBinaryOperators) {
        if (binary.kind == kind) {
            return &binary;
        }
    }
    return nullptr;
}

}  // namespace

Parser::Parser(std::vector<Token> tokens, std::vector<Diagnostic>& diagnostics)
    : tokens_(std::move(tokens)), diagnostics_(diagnostics) {
    if (tokens_.empty() || !tokens_.back().is(TokenKind::EndOfFile)) {
        tokens_.emplace_back();
    }
}

const Token& Parser::peek(std::size_t ahead) const {
    std::size_t index = pos_ + ahead;
    return index < tokens_.size() ? tokens_[index] : tokens_.back();
}

const Token& Parser::advance() {
    const Token& token = tokens_[pos_];
    if (pos_ + 1 < tokens_.size()) {
        ++pos_;
    }
    return token;
}

void Parser::skipNewlines() {
    while (at(TokenKind::Newline)) {
        advance();
    }
}

void Parser::error(std::string code, std::string message, const SourceLocation& location,
                   std::string label) {
    if (failed_) {
        return;
    }
    failed_ = true;
    addError(diagnostics_, std::move(code), std::move(message), location, std::move(label));
}

// Skips the rest of a broken statement: up to and including the end of its line (or ';'),
// or up to (excluding) the '}' closing the enclosing block. Delimiters the statement opened
// are skipped as a whole, so a broken list spanning lines is dropped in one piece.
void Parser::synchronize(std::size_t base) {
    while (!at(TokenKind::EndOfFile)) {
        TokenKind kind = peek().kind;
        if (open_.size() <= base) {
            if (kind == TokenKind::Newline || kind == TokenKind::Semicolon) {
                advance();
                return;
            }
            if (kind == TokenKind::RBrace && base > 0) {
                return;
            }
        }
        if (isOpener(kind)) {
            open_.push_back(peek());
        } else if (isCloser(kind) && open_.size() > base) {
            TokenKind expected = open_.back().is(TokenKind::LBrace)     ? TokenKind::RBrace
                                 : open_.back().is(TokenKind::LBracket) ? TokenKind::RBracket
                                                                        : TokenKind::RParen;
            open_.pop_back();
            if (kind != expected) {
                // The statement left this delimiter open; the closer belongs further out.
                continue;
            }
        }
        advance();
    }
    if (open_.size() > base) {
        open_.resize(base);
    }
}

bool Parser::expectStatementEnd(std::size_t base) {
    if (peek().closesLine() || (base > 0 && at(TokenKind::RBrace))) {
        if (!at(TokenKind::RBrace) && !at(TokenKind::EndOfFile)) {
            advance();
        }
        return true;
    }
    error("E0101", "expected end of line or ';', found " + describeToken(peek()), peek().location,
          "unexpected here");
    synchronize(base);
    return false;
}

FileNode Parser::parseFile() {
    FileNode file;
    while (true) {
        while (at(TokenKind::Newline) || at(TokenKind::Semicolon)) {
            advance();
        }
        if (at(TokenKind::EndOfFile)) {
            break;
        }
        failed_ = false;
        bool discard = false;
        if (at(TokenKind::SlashDash)) {
            advance();
            skipNewlines();
            discard = true;
        }
        const Token& first = peek();
        if (first.is(TokenKind::Identifier) && first.text == "import" &&
            !peek(1).is(TokenKind::Equals)) {
            ImportNode import;
            if (parseImport(import) && expectStatementEnd(0) && !discard) {
                file.statements.emplace_back(std::move(import));
            }
        } else if (first.is(TokenKind::Identifier) && first.text == "param") {
            ParamNode param;
            if (parseParam(param) && expectStatementEnd(0) && !discard) {
                file.statements.emplace_back(std::move(param));
            }
        } else if (first.is(TokenKind::Identifier) && peek(1).is(TokenKind::Equals)) {
            error("E0104", "attribute '" + first.text + "' outside of a block", first.location,
                  "attributes belong inside a block such as 'project { ... }'");
            synchronize(0);
        } else if (first.is(TokenKind::Identifier)) {
            BlockNode block;
            if (parseBlock(block) && expectStatementEnd(0) && !discard) {
                file.statements.emplace_back(std::move(block));
            }
        } else if (first.is(TokenKind::RBrace)) {
            error("E0101", "unexpected '}'", first.location, "no block is open here");
            advance();
        } else {
            error("E0101", "expected a block or 'param', found " + describeToken(first),
                  first.location, "expected a statement");
            synchronize(0);
            // A statement cannot start with a closer; skip it so the loop makes progress.
            if (isCloser(peek().kind)) {
                advance();
            }
        }
    }
    return file;
}

ExprPtr Parser::parseLoneExpression() {
    failed_ = false;
    skipNewlines();
    ExprPtr expr = parseExpression();
    if (!expr) {
        return nullptr;
    }
    skipNewlines();
    if (!at(TokenKind::EndOfFile)) {
        error("E0101", "expected end of value, found " + describeToken(peek()), peek().location,
              "unexpected here");
        return nullptr;
    }
    return expr;
}

bool Parser::parseImport(ImportNode& import) {
    advance();  // 'import'
    if (!at(TokenKind::String)) {
        error("E0101", "expected a file name after 'import', found " + describeToken(peek()),
              peek().location, "write 'import \"file.sylva\" as name'");
        synchronize(0);
        return false;
    }
    import.path = peek().text;
    import.pathLocation = advance().location;
    if (at(TokenKind::Identifier) && peek().text == "as") {
        advance();
        if (!at(TokenKind::Identifier)) {
            error("E0101", "expected a namespace after 'as', found " + describeToken(peek()),
                  peek().location, "expected a name");
            synchronize(0);
            return false;
        }
        import.alias = peek().text;
        import.aliasLocation = advance().location;
    }
    return true;
}

bool Parser::parseParam(ParamNode& param) {
    advance();  // 'param'
    if (!at(TokenKind::Identifier)) {
        error("E0101", "expected a param name, found " + describeToken(peek()), peek().location,
              "expected a name");
        synchronize(0);
        return false;
    }
    param.name = peek().text;
    param.nameLocation = advance().location;
    if (at(TokenKind::Colon)) {
        advance();
        if (!at(TokenKind::Identifier)) {
            error("E0101", "expected a param type, found " + describeToken(peek()), peek().location,
                  "expected a type such as 'length'");
            synchronize(0);
            return false;
        }
        param.type = peek().text;
        param.typeLocation = advance().location;
    }
    if (at(TokenKind::Equals)) {
        advance();
        param.defaultValue = parseExpression();
        if (!param.defaultValue) {
            synchronize(0);
            return false;
        }
    }
    if (at(TokenKind::String)) {
        param.doc = advance().text;
    }
    return true;
}

bool Parser::parseBlock(BlockNode& block) {
    block.keyword = peek().text;
    block.keywordLocation = advance().location;
    if (at(TokenKind::Identifier)) {
        block.name = peek().text;
        block.nameLocation = advance().location;
    }
    if (at(TokenKind::Colon)) {
        advance();
        if (!at(TokenKind::Identifier)) {
            error("E0101", "expected a kind after ':', found " + describeToken(peek()),
                  peek().location, "expected a kind such as 'noise'");
            synchronize(0);
            return false;
        }
        block.kind = peek().text;
        block.kindLocation = advance().location;
    }
    if (at(TokenKind::Identifier) && peek().text == "extends") {
        advance();
        if (!at(TokenKind::Identifier) && !at(TokenKind::Reference)) {
            error("E0101", "expected a name after 'extends', found " + describeToken(peek()),
                  peek().location, "expected the name of the parent");
            synchronize(0);
            return false;
        }
        block.extends = peek().text;
        if (at(TokenKind::Reference) && !peek().field.empty()) {
            block.extends += "." + peek().field;
        }
        block.extendsLocation = advance().location;
    }
    if (!at(TokenKind::LBrace)) {
        error("E0101", "expected '{' after '" + block.keyword + "', found " + describeToken(peek()),
              peek().location, "expected '{'");
        synchronize(0);
        return false;
    }
    parseBody(block, true);
    return true;
}

void Parser::parseBody(BlockNode& block, bool allowOverrides) {
    const Token opener = advance();
    open_.push_back(opener);
    const std::size_t base = open_.size();
    while (true) {
        while (at(TokenKind::Newline) || at(TokenKind::Semicolon)) {
            advance();
        }
        if (at(TokenKind::RBrace)) {
            advance();
            open_.resize(base - 1);
            return;
        }
        if (at(TokenKind::EndOfFile)) {
            failed_ = false;
            error("E0102", "unclosed '{'", opener.location, "this '{' is never closed");
            open_.resize(base - 1);
            return;
        }
        failed_ = false;
        bool discard = false;
        if (at(TokenKind::SlashDash)) {
            advance();
            skipNewlines();
            discard = true;
        }
        const Token& name = peek();
        const TokenKind assign = peek(1).kind;
        const bool renderOverride = peek(1).is(TokenKind::Identifier) && peek(1).text == "render";
        if (name.is(TokenKind::Identifier) && name.text == "override" &&
            (peek(1).is(TokenKind::Reference) || renderOverride) && allowOverrides) {
            OverrideNode override;
            override.render = renderOverride;
            override.target = peek(1).text + (peek(1).field.empty() ? "" : "." + peek(1).field);
            override.targetLocation = peek(1).location;
            advance();
            advance();
            if (!at(TokenKind::LBrace)) {
                error("E0101",
                      std::string("expected '{' after 'override ") + (renderOverride ? "" : "@") +
                          override.target + "', found " + describeToken(peek()),
                      peek().location, "expected '{'");
                synchronize(base);
                continue;
            }
            BlockNode body;
            parseBody(body, false);
            override.attributes = std::move(body.attributes);
            if (expectStatementEnd(base) && !discard) {
                block.overrides.push_back(std::move(override));
            }
        } else if (name.is(TokenKind::Identifier) &&
                   (assign == TokenKind::Equals || assign == TokenKind::PlusEquals ||
                    assign == TokenKind::MinusEquals)) {
            AttributeNode attribute;
            attribute.name = name.text;
            attribute.nameLocation = name.location;
            attribute.op = assign == TokenKind::Equals       ? AssignOp::Set
                           : assign == TokenKind::PlusEquals ? AssignOp::Append
                                                             : AssignOp::Remove;
            attribute.opLocation = peek(1).location;
            advance();
            advance();
            attribute.value = parseExpression();
            if (!attribute.value) {
                synchronize(base);
                continue;
            }
            if (expectStatementEnd(base) && !discard) {
                block.attributes.push_back(std::move(attribute));
            }
        } else if (name.is(TokenKind::Identifier)) {
            error("E0101",
                  "expected '=' after attribute name '" + name.text + "', found " +
                      describeToken(peek(1)),
                  peek(1).location, "expected '='");
            synchronize(base);
        } else {
            error("E0101", "expected an attribute name, found " + describeToken(name),
                  name.location, "expected 'name = value'");
            synchronize(base);
        }
    }
}

ExprPtr Parser::parseExpression(int minBindingPower) {
    if (depth_ >= kMaxNesting) {
        error("E0103", "expression nested too deeply", peek().location,
              "nesting is limited to " + std::to_string(kMaxNesting) + " levels");
        return nullptr;
    }
    ++depth_;
    ExprPtr left = parsePrefix();
    if (left) {
        left = parsePostfix(std::move(left));
    }
    while (left) {
        const TokenKind kind = peek().kind;
        const BinaryOperator* binary = binaryOperator(kind);
        if (!binary || binary->power <= minBindingPower) {
            break;
        }
        advance();
        if (kind == TokenKind::Question) {
            left = parseConditional(std::move(left));
            continue;
        }
        ExprPtr right = parseExpression(binary->power);
        if (!right) {
            left = nullptr;
            break;
        }
        auto node = makeExpr(Expr::Kind::Binary, spanLocations(left->location, right->location));
        node->op = binary->op;
        node->children.push_back(std::move(left));
        node->children.push_back(std::move(right));
        left = std::move(node);
    }
    --depth_;
    return left;
}

// `c ? a : b` after the '?', right-associative: `a ? b : c ? d : e` nests in the else branch.
ExprPtr Parser::parseConditional(ExprPtr condition) {
    skipNewlines();
    ExprPtr then = parseExpression(0);
    if (!then) {
        return nullptr;
    }
    skipNewlines();
    if (!at(TokenKind::Colon)) {
        error("E0101", "expected ':' in conditional, found " + describeToken(peek()),
              peek().location, "write 'condition ? then : else'");
        return nullptr;
    }
    advance();
    skipNewlines();
    ExprPtr otherwise = parseExpression(0);
    if (!otherwise) {
        return nullptr;
    }
    auto conditional =
        makeExpr(Expr::Kind::Conditional, spanLocations(condition->location, otherwise->location));
    conditional->children.push_back(std::move(condition));
    conditional->children.push_back(std::move(then));
    conditional->children.push_back(std::move(otherwise));
    return conditional;
}

ExprPtr Parser::parsePrefix() {
    const Token& token = peek();
    if (token.malformed) {
        // The lexer already reported it; drop the statement without a second error.
        failed_ = true;
        return nullptr;
    }
    switch (token.kind) {
        case TokenKind::Number: {
            auto expr = makeExpr(Expr::Kind::Number, token.location);
            expr->number = token.number;
            expr->dimension = token.dimension;
            advance();
            return expr;
        }
        case TokenKind::String: {
            auto expr = makeExpr(Expr::Kind::String, token.location);
            expr->text = token.text;
            advance();
            return expr;
        }
        case TokenKind::DateTime: {
            auto expr = makeExpr(Expr::Kind::DateTime, token.location);
            expr->text = token.text;
            advance();
            return expr;
        }
        case TokenKind::Color: {
            auto expr = makeExpr(Expr::Kind::Color, token.location);
            expr->color = token.color;
            advance();
            return expr;
        }
        case TokenKind::Reference: {
            auto expr = makeExpr(Expr::Kind::Reference, token.location);
            expr->text = token.text;
            expr->field = token.field;
            advance();
            return expr;
        }
        case TokenKind::Identifier: {
            if (peek(1).is(TokenKind::LParen)) {
                return parseCall();
            }
            if (token.text == "true" || token.text == "false") {
                auto expr = makeExpr(Expr::Kind::Bool, token.location);
                expr->boolean = token.text == "true";
                advance();
                return expr;
            }
            auto expr = makeExpr(Expr::Kind::Word, token.location);
            expr->text = token.text;
            advance();
            return expr;
        }
        case TokenKind::LBracket:
            return parseList();
        case TokenKind::LBrace:
            return parseObject();
        case TokenKind::LParen: {
            const Token opener = advance();
            open_.push_back(opener);
            skipNewlines();
            ExprPtr inner = parseExpression();
            if (!inner) {
                return nullptr;
            }
            skipNewlines();
            if (!closeDelimiter(TokenKind::RParen, opener, *inner)) {
                return nullptr;
            }
            return inner;
        }
        case TokenKind::Minus:
        case TokenKind::Bang:
        case TokenKind::Plus: {
            const Token sign = advance();
            ExprPtr operand = parseExpression(30);
            if (!operand) {
                return nullptr;
            }
            auto expr =
                makeExpr(Expr::Kind::Unary, spanLocations(sign.location, operand->location));
            expr->op = sign.text[0];
            expr->children.push_back(std::move(operand));
            return expr;
        }
        default:
            error("E0101", "expected a value, found " + describeToken(token), token.location,
                  "expected a value");
            return nullptr;
    }
}

// Consumes `closer` for `opener`; reports E0102 at end of file and E0101 otherwise.
bool Parser::closeDelimiter(TokenKind closer, const Token& opener, Expr& node) {
    if (at(closer)) {
        // A parenthesised value keeps its own range; containers cover their delimiters.
        if (node.kind == Expr::Kind::List || node.kind == Expr::Kind::Object ||
            node.kind == Expr::Kind::Call) {
            node.location = spanLocations(opener.location, peek().location);
        }
        advance();
        open_.pop_back();
        return true;
    }
    if (at(TokenKind::EndOfFile) || (isCloser(peek().kind) && !at(closer))) {
        error("E0102", "unclosed '" + opener.text + "'", opener.location,
              "this '" + opener.text + "' is never closed");
        return false;
    }
    const char* closeText = closer == TokenKind::RParen     ? "')'"
                            : closer == TokenKind::RBracket ? "']'"
                                                            : "'}'";
    error("E0101", std::string("expected ',' or ") + closeText + ", found " + describeToken(peek()),
          peek().location, "expected ',' or " + std::string(closeText));
    return false;
}

ExprPtr Parser::parseList() {
    const Token opener = advance();
    open_.push_back(opener);
    auto list = makeExpr(Expr::Kind::List, opener.location);
    while (true) {
        skipNewlines();
        if (at(TokenKind::RBracket)) {
            break;
        }
        if (at(TokenKind::EndOfFile)) {
            break;
        }
        ExprPtr element = parseExpression();
        if (!element) {
            return nullptr;
        }
        if (list->children.size() >= kMaxListLength) {
            error("E0105", "list too long", element->location,
                  "lists are limited to " + std::to_string(kMaxListLength) + " elements");
            return nullptr;
        }
        list->children.push_back(std::move(element));
        skipNewlines();
        if (!at(TokenKind::Comma)) {
            break;
        }
        advance();
    }
    return closeDelimiter(TokenKind::RBracket, opener, *list) ? std::move(list) : nullptr;
}

ExprPtr Parser::parseObject() {
    const Token opener = advance();
    open_.push_back(opener);
    auto object = makeExpr(Expr::Kind::Object, opener.location);
    while (true) {
        while (at(TokenKind::Newline) || at(TokenKind::Comma)) {
            advance();
        }
        if (at(TokenKind::RBrace) || at(TokenKind::EndOfFile)) {
            break;
        }
        if (!at(TokenKind::Identifier) && !at(TokenKind::String)) {
            error("E0101", "expected a key, found " + describeToken(peek()), peek().location,
                  "expected 'key = value'");
            return nullptr;
        }
        std::pair<std::string, SourceLocation> key{peek().text, peek().location};
        advance();
        if (!at(TokenKind::Equals)) {
            error("E0101",
                  "expected '=' after key '" + key.first + "', found " + describeToken(peek()),
                  peek().location, "expected '='");
            return nullptr;
        }
        advance();
        skipNewlines();
        ExprPtr value = parseExpression();
        if (!value) {
            return nullptr;
        }
        object->keys.push_back(std::move(key));
        object->children.push_back(std::move(value));
        if (!at(TokenKind::Comma) && !at(TokenKind::Newline)) {
            break;
        }
    }
    return closeDelimiter(TokenKind::RBrace, opener, *object) ? std::move(object) : nullptr;
}

// `value[index]` and `value.field` after any primary (references carry their fields
// already: `@beach.position`).
ExprPtr Parser::parsePostfix(ExprPtr left) {
    while (left) {
        if (at(TokenKind::LBracket) && !peek().spaceBefore) {
            const Token opener = advance();
            open_.push_back(opener);
            ExprPtr index = parseExpression();
            if (!index) {
                return nullptr;
            }
            auto node = makeExpr(Expr::Kind::Index, left->location);
            node->children.push_back(std::move(left));
            node->children.push_back(std::move(index));
            if (!at(TokenKind::RBracket)) {
                Expr& ref = *node;
                closeDelimiter(TokenKind::RBracket, opener, ref);
                return nullptr;
            }
            node->location = spanLocations(node->location, peek().location);
            advance();
            open_.pop_back();
            left = std::move(node);
        } else if (at(TokenKind::Dot) && peek(1).is(TokenKind::Identifier)) {
            advance();
            const Token& field = advance();
            auto node = makeExpr(Expr::Kind::Field, spanLocations(left->location, field.location));
            node->text = field.text;
            node->children.push_back(std::move(left));
            left = std::move(node);
        } else {
            break;
        }
    }
    return left;
}

ExprPtr Parser::parseCall() {
    const Token name = advance();
    const Token opener = advance();
    open_.push_back(opener);
    auto call = makeExpr(Expr::Kind::Call, name.location);
    call->text = name.text;
    while (true) {
        skipNewlines();
        if (at(TokenKind::RParen) || at(TokenKind::EndOfFile)) {
            break;
        }
        ExprPtr argument = parseExpression();
        if (!argument) {
            return nullptr;
        }
        call->children.push_back(std::move(argument));
        skipNewlines();
        if (!at(TokenKind::Comma)) {
            break;
        }
        advance();
    }
    if (!closeDelimiter(TokenKind::RParen, opener, *call)) {
        return nullptr;
    }
    call->location = spanLocations(name.location, call->location);
    return call;
}

}  // namespace sylva::dsl
