#include "sylva/dsl/Formatter.h"

#include <memory>
#include <string>
#include <vector>

#include "sylva/dsl/Lexer.h"
#include "sylva/dsl/Parser.h"

namespace sylva::dsl {

namespace {

bool isOpener(TokenKind kind) {
    return kind == TokenKind::LBrace || kind == TokenKind::LBracket || kind == TokenKind::LParen;
}
bool isCloser(TokenKind kind) {
    return kind == TokenKind::RBrace || kind == TokenKind::RBracket || kind == TokenKind::RParen;
}
bool isValueEnd(TokenKind kind) {
    switch (kind) {
        case TokenKind::Identifier:
        case TokenKind::Number:
        case TokenKind::String:
        case TokenKind::Color:
        case TokenKind::Reference:
        case TokenKind::DateTime:
        case TokenKind::RBracket:
        case TokenKind::RParen:
        case TokenKind::RBrace:
            return true;
        default:
            return false;
    }
}

// A '-', '+' or '!' that is a sign, not a binary operator: nothing value-like before it.
bool isUnary(const Token* before, const Token& token) {
    if (token.kind == TokenKind::Bang) {
        return true;
    }
    if (token.kind != TokenKind::Minus && token.kind != TokenKind::Plus) {
        return false;
    }
    return before == nullptr || !isValueEnd(before->kind);
}

std::string raw(std::string_view text, const Token& token) {
    if (token.kind == TokenKind::Comment) {
        return token.text;
    }
    return std::string(text.substr(token.offset, token.location.length));
}

// Lines of tokens: a line is the tokens between two Newline tokens.
std::vector<std::vector<const Token*>> splitLines(const std::vector<Token>& tokens) {
    std::vector<std::vector<const Token*>> lines(1);
    for (const Token& token : tokens) {
        if (token.kind == TokenKind::EndOfFile) {
            break;
        }
        if (token.kind == TokenKind::Newline) {
            lines.emplace_back();
        } else {
            lines.back().push_back(&token);
        }
    }
    return lines;
}

// A bracket still open at the end of a line.
struct Open {
    TokenKind kind;
    int indent;  // indentation of the line that opened it
    int line;
};

// Indentation: one level inside the innermost bracket still open from an earlier line; a
// line starting with closers sits at the level of the line that opened them.
int indentOf(const std::vector<const Token*>& line, const std::vector<Open>& open) {
    std::size_t depth = open.size();
    for (const Token* token : line) {
        if (!isCloser(token->kind) || depth == 0) {
            break;
        }
        --depth;
    }
    if (depth < open.size()) {
        return open[depth].indent;
    }
    return open.empty() ? 0 : open.back().indent + 4;
}

// Whether one space separates `token` from `previous` (after `beforePrevious`).
bool spaceBetween(const Token* beforePrevious, const Token& previous, const Token& token) {
    TokenKind p = previous.kind;
    TokenKind c = token.kind;
    if (c == TokenKind::Comment) {
        return true;
    }
    if (p == TokenKind::LParen || p == TokenKind::LBracket || p == TokenKind::Dot ||
        c == TokenKind::RParen || c == TokenKind::RBracket || c == TokenKind::Comma ||
        c == TokenKind::Semicolon || c == TokenKind::Dot) {
        return false;
    }
    if (c == TokenKind::LParen && p == TokenKind::Identifier) {
        return false;  // a call
    }
    if (c == TokenKind::LBracket && isValueEnd(p) && !token.spaceBefore) {
        return false;  // an index
    }
    if (p == TokenKind::LBrace && c == TokenKind::RBrace) {
        return false;
    }
    return !isUnary(beforePrevious, previous);
}

}  // namespace

std::optional<std::string> Formatter::format(std::string_view input, const std::string& displayName,
                                             SourceFiles& sources,
                                             std::vector<Diagnostic>& diagnostics) {
    std::shared_ptr<const std::string> file = sources.add(displayName, std::string(input));
    std::string_view text = sources.text(file);
    const std::size_t before = diagnostics.size();
    {
        // The parser checks the syntax; fmt never rewrites text it does not understand.
        std::vector<Token> tokens = Lexer(text, file, diagnostics).tokenize();
        Parser(std::move(tokens), diagnostics).parseFile();
    }
    if (diagnostics.size() != before) {
        return std::nullopt;
    }
    Lexer lexer(text, file, diagnostics);
    lexer.keepComments(true);
    std::vector<Token> tokens = lexer.tokenize();
    const std::vector<std::vector<const Token*>> lines = splitLines(tokens);

    std::vector<Open> open;
    std::string out;
    bool pendingBlank = false;
    for (std::size_t lineIndex = 0; lineIndex < lines.size(); ++lineIndex) {
        const std::vector<const Token*>& line = lines[lineIndex];
        if (line.empty()) {
            pendingBlank = !out.empty();
            continue;
        }
        const int indent = indentOf(line, open);
        // At most one blank line, and none right after an opening bracket.
        if (pendingBlank && !out.empty() && !isCloser(line.front()->kind)) {
            const bool afterOpener =
                out.size() >= 2 && (out[out.size() - 2] == '{' || out[out.size() - 2] == '[' ||
                                    out[out.size() - 2] == '(');
            if (!afterOpener) {
                out += "\n";
            }
        }
        pendingBlank = false;
        std::string text_line(static_cast<std::size_t>(indent), ' ');
        const Token* previous = nullptr;
        const Token* beforePrevious = nullptr;
        for (const Token* token : line) {
            if (previous && spaceBetween(beforePrevious, *previous, *token)) {
                text_line += ' ';
            }
            text_line += raw(text, *token);
            if (isOpener(token->kind)) {
                open.push_back({token->kind, indent, static_cast<int>(lineIndex)});
            } else if (isCloser(token->kind) && !open.empty()) {
                open.pop_back();
            }
            beforePrevious = previous;
            previous = token;
        }
        // Multi-line block comments keep their inner lines as written.
        out += text_line;
        out += "\n";
    }
    return out;
}

}  // namespace sylva::dsl
