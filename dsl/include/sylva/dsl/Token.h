// Tokens produced by the Lexer. Numbers are already normalised to SI with their
// dimension; strings are already unescaped.
#pragma once

#include <string>

#include "sylva/core/base/SourceLocation.h"
#include "sylva/core/model/Value.h"

namespace sylva::dsl {

enum class TokenKind {
    Identifier,
    Number,
    String,
    Color,
    Reference,  // @name or @name.field
    LBrace,
    RBrace,
    LBracket,
    RBracket,
    LParen,
    RParen,
    Comma,
    Equals,
    Colon,
    Semicolon,
    Plus,
    Minus,
    Star,
    Slash,
    SlashDash,  // `/-`: comments out the next attribute or block
    Newline,
    EndOfFile,
    Percent,       // `%` as the remainder operator (after a digit it is a unit)
    EqualEqual,    // ==
    BangEqual,     // !=
    Less,          // <
    LessEqual,     // <=
    Greater,       // >
    GreaterEqual,  // >=
    AndAnd,        // &&
    OrOr,          // ||
    Bang,          // !
    Question,      // ?
    PlusEquals,    // +=
    MinusEquals,   // -=
    Dot,           // . (field access after a call or a parenthesis)
    DateTime,      // 2024-06-21T14:30+02:00 or 14:30; text holds the canonical ISO form
    Comment,       // only with Lexer::keepComments(): `#`, `//` or `/* */` text
};

struct Token {
    TokenKind kind = TokenKind::EndOfFile;
    std::string text;   // identifier / reference name / unescaped string / source text
    std::string field;  // for Reference: the part after the first '.' (may hold more dots)
    SourceLocation location;
    double number = 0.0;  // for Number: value in SI units
    Dimension dimension = Dimension::None;
    Color color;
    bool malformed = false;    // a lexical error was reported for this token
    bool spaceBefore = false;  // whitespace or a line start precedes the token (formatter)
    std::size_t offset = 0;    // byte offset of the token in its text

    bool is(TokenKind k) const { return kind == k; }
    bool closesLine() const {
        return kind == TokenKind::Newline || kind == TokenKind::Semicolon ||
               kind == TokenKind::EndOfFile;
    }
};

// How a token is named in syntax errors: "'}'", "identifier 'foo'", "end of line".
std::string describeToken(const Token& token);

}  // namespace sylva::dsl
