// Recursive-descent parser for statements and a Pratt parser for expressions.
// Syntax errors (E01xx) are appended to the diagnostics; the parser reports at most one
// error per statement and then recovers at the end of the line or at the '}' that
// closes the current block, so one run reports every broken statement.
// Expression nesting is limited to kMaxNesting levels (E0103).
#pragma once

#include <vector>

#include "sylva/dsl/Ast.h"
#include "sylva/dsl/Diagnostic.h"
#include "sylva/dsl/Token.h"

namespace sylva::dsl {

class Parser {
public:
    static constexpr int kMaxNesting = 64;
    // Elements of one list literal (E0105): keeps a hostile file from growing the AST
    // without bound through one giant list.
    static constexpr std::size_t kMaxListLength = 100000;

    // `tokens` must end with an EndOfFile token (as Lexer::tokenize produces).
    Parser(std::vector<Token> tokens, std::vector<Diagnostic>& diagnostics);

    FileNode parseFile();
    // The whole token stream as one expression (for -D values); null after an error.
    ExprPtr parseLoneExpression();

private:
    const Token& peek(std::size_t ahead = 0) const;
    const Token& advance();
    bool at(TokenKind kind) const { return peek().kind == kind; }
    void skipNewlines();
    void error(std::string code, std::string message, const SourceLocation& location,
               std::string label = {});
    void synchronize(std::size_t base);
    bool expectStatementEnd(std::size_t base);

    bool parseParam(ParamNode& param);
    bool parseImport(ImportNode& import);
    bool parseBlock(BlockNode& block);
    void parseBody(BlockNode& block, bool allowOverrides);

    ExprPtr parseExpression(int minBindingPower = 0);
    ExprPtr parseConditional(ExprPtr condition);
    ExprPtr parsePrefix();
    ExprPtr parseList();
    ExprPtr parseObject();
    ExprPtr parseCall();
    ExprPtr parsePostfix(ExprPtr left);
    bool closeDelimiter(TokenKind closer, const Token& opener, Expr& node);

    std::vector<Token> tokens_;
    std::vector<Diagnostic>& diagnostics_;
    std::size_t pos_ = 0;
    bool failed_ = false;      // an error was reported in the current statement
    std::vector<Token> open_;  // delimiters opened and not yet closed, for recovery
    int depth_ = 0;
};

}  // namespace sylva::dsl
