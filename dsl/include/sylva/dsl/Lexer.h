// Turns UTF-8 project text into tokens. Lexical errors (E0004..E0009) are appended to
// the diagnostics and lexing continues, so one run reports every problem. The text
// must already be valid UTF-8 (the loader checks, E0003).
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "sylva/dsl/Diagnostic.h"
#include "sylva/dsl/Token.h"

namespace sylva::dsl {

class Lexer {
public:
    // Lexes text[startOffset..]; locations name `file` and count from line 1 column 1 of text.
    Lexer(std::string_view text, std::shared_ptr<const std::string> file,
          std::vector<Diagnostic>& diagnostics, std::size_t startOffset = 0);

    // All tokens, always ending with one EndOfFile token.
    std::vector<Token> tokenize();
    // Also emit Comment tokens (for the formatter; the parser does not accept them).
    void keepComments(bool keep) { keepComments_ = keep; }

private:
    SourceLocation locationAt(std::size_t offset, std::size_t length) const;
    void push(TokenKind kind, std::size_t start, std::size_t length);
    bool colourContext() const;
    void lexToken();
    void lexLineComment();   // `#` (not a colour) or `//` to the end of the line
    void lexBlockComment();  // `/* ... */`, nested
    void lexReference();     // `@name`, `@ns.name.field`
    void lexPunctuation(char c, char next);
    void lexNumber();
    bool lexDateTime();
    void lexString();
    void lexColour();
    void skipBlockComment();
    void lexUnexpected();

    std::string_view text_;
    std::shared_ptr<const std::string> file_;
    std::vector<Diagnostic>& diagnostics_;
    std::size_t pos_ = 0;
    std::uint32_t line_ = 1;
    std::size_t lineStart_ = 0;
    std::vector<Token> tokens_;
    bool keepComments_ = false;
    std::size_t lastEnd_ = 0;  // end offset of the previous token, for spaceBefore
};

}  // namespace sylva::dsl
