#include "sylva/dsl/Token.h"

namespace sylva::dsl {

std::string describeToken(const Token& token) {
    switch (token.kind) {
        case TokenKind::Identifier:
            return "identifier '" + token.text + "'";
        case TokenKind::Number:
            return "number";
        case TokenKind::String:
            return "string";
        case TokenKind::Color:
            return "colour";
        case TokenKind::Reference:
            return "reference '@" + token.text + "'";
        case TokenKind::LBrace:
            return "'{'";
        case TokenKind::RBrace:
            return "'}'";
        case TokenKind::LBracket:
            return "'['";
        case TokenKind::RBracket:
            return "']'";
        case TokenKind::LParen:
            return "'('";
        case TokenKind::RParen:
            return "')'";
        case TokenKind::Comma:
            return "','";
        case TokenKind::Equals:
            return "'='";
        case TokenKind::Colon:
            return "':'";
        case TokenKind::Semicolon:
            return "';'";
        case TokenKind::Plus:
            return "'+'";
        case TokenKind::Minus:
            return "'-'";
        case TokenKind::Star:
            return "'*'";
        case TokenKind::Slash:
            return "'/'";
        case TokenKind::SlashDash:
            return "'/-'";
        case TokenKind::Newline:
            return "end of line";
        case TokenKind::EndOfFile:
            return "end of file";
        case TokenKind::DateTime:
            return "date/time";
        case TokenKind::Comment:
            return "comment";
        case TokenKind::Percent:
        case TokenKind::EqualEqual:
        case TokenKind::BangEqual:
        case TokenKind::Less:
        case TokenKind::LessEqual:
        case TokenKind::Greater:
        case TokenKind::GreaterEqual:
        case TokenKind::AndAnd:
        case TokenKind::OrOr:
        case TokenKind::Bang:
        case TokenKind::Question:
        case TokenKind::PlusEquals:
        case TokenKind::MinusEquals:
        case TokenKind::Dot:
            return "'" + token.text + "'";
    }
    return "token";
}

}  // namespace sylva::dsl
