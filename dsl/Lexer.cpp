#include "sylva/dsl/Lexer.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <utility>

namespace sylva::dsl {

namespace {

bool isIdentStart(char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '_';
}
bool isDigit(char c) {
    return c >= '0' && c <= '9';
}
bool isIdentChar(char c) {
    return isIdentStart(c) || isDigit(c);
}
bool isHex(char c) {
    return isDigit(c) || (c >= 'a' && c <= 'f') || (c >= 'A' && c <= 'F');
}
int hexValue(char c) {
    if (isDigit(c)) {
        return c - '0';
    }
    return (c | 0x20) - 'a' + 10;
}

struct Unit {
    const char* name;
    double scale;  // to SI
    Dimension dimension;
};

constexpr Unit kUnits[] = {
    {"m", 1.0, Dimension::Length},
    {"km", 1000.0, Dimension::Length},
    {"cm", 0.01, Dimension::Length},
    {"mm", 0.001, Dimension::Length},
    {"deg", std::numbers::pi / 180.0, Dimension::Angle},
    {"rad", 1.0, Dimension::Angle},
    {"%", 0.01, Dimension::Ratio},
    {"px", 1.0, Dimension::Pixels},
    {"s", 1.0, Dimension::Time},
    {"min", 60.0, Dimension::Time},
    {"h", 3600.0, Dimension::Time},
};

// Operators and delimiters; the two-character forms come first, so `==` wins over `=`.
// A lone '&' or '|' is no token (the operators are '&&' and '||').
struct Punctuation {
    char first;
    char second;  // '\0' for one-character tokens
    TokenKind kind;
};

constexpr Punctuation kPunctuation[] = {
    {'=', '=', TokenKind::EqualEqual}, {'!', '=', TokenKind::BangEqual},
    {'<', '=', TokenKind::LessEqual},  {'>', '=', TokenKind::GreaterEqual},
    {'&', '&', TokenKind::AndAnd},     {'|', '|', TokenKind::OrOr},
    {'+', '=', TokenKind::PlusEquals}, {'-', '=', TokenKind::MinusEquals},
    {'{', '\0', TokenKind::LBrace},    {'}', '\0', TokenKind::RBrace},
    {'[', '\0', TokenKind::LBracket},  {']', '\0', TokenKind::RBracket},
    {'(', '\0', TokenKind::LParen},    {')', '\0', TokenKind::RParen},
    {',', '\0', TokenKind::Comma},     {'=', '\0', TokenKind::Equals},
    {'!', '\0', TokenKind::Bang},      {'<', '\0', TokenKind::Less},
    {'>', '\0', TokenKind::Greater},   {'?', '\0', TokenKind::Question},
    {'%', '\0', TokenKind::Percent},   {'.', '\0', TokenKind::Dot},
    {':', '\0', TokenKind::Colon},     {';', '\0', TokenKind::Semicolon},
    {'+', '\0', TokenKind::Plus},      {'-', '\0', TokenKind::Minus},
    {'*', '\0', TokenKind::Star},      {'/', '\0', TokenKind::Slash},
};

std::size_t utf8Length(unsigned char lead) {
    if (lead < 0x80) {
        return 1;
    }
    if ((lead & 0xE0) == 0xC0) {
        return 2;
    }
    if ((lead & 0xF0) == 0xE0) {
        return 3;
    }
    return 4;
}

}  // namespace

Lexer::Lexer(std::string_view text, std::shared_ptr<const std::string> file,
             std::vector<Diagnostic>& diagnostics, std::size_t startOffset)
    : text_(text), file_(std::move(file)), diagnostics_(diagnostics), pos_(startOffset) {}

SourceLocation Lexer::locationAt(std::size_t offset, std::size_t length) const {
    SourceLocation location;
    location.file = file_;
    location.line = line_;
    location.column = static_cast<std::uint32_t>(offset - lineStart_ + 1);
    location.length = static_cast<std::uint32_t>(length);
    return location;
}

void Lexer::push(TokenKind kind, std::size_t start, std::size_t length) {
    Token token;
    token.kind = kind;
    token.text = std::string(text_.substr(start, length));
    token.location = locationAt(start, length);
    token.offset = start;
    token.spaceBefore = start != lastEnd_ || start == lineStart_;
    lastEnd_ = start + length;
    tokens_.push_back(std::move(token));
}

bool Lexer::colourContext() const {
    if (tokens_.empty()) {
        return false;
    }
    switch (tokens_.back().kind) {
        case TokenKind::Equals:
        case TokenKind::Comma:
        case TokenKind::LBracket:
        case TokenKind::LParen:
        case TokenKind::Colon:
        case TokenKind::Plus:
        case TokenKind::Minus:
        case TokenKind::Star:
        case TokenKind::Slash:
            return true;
        default:
            return false;
    }
}

std::vector<Token> Lexer::tokenize() {
    // A byte order mark is not part of the text.
    if (pos_ == 0 && text_.substr(0, 3) == "\xEF\xBB\xBF") {
        pos_ = 3;
    }
    while (pos_ < text_.size()) {
        lexToken();
    }
    Token end;
    end.kind = TokenKind::EndOfFile;
    end.location = locationAt(pos_, 0);
    tokens_.push_back(std::move(end));
    return std::move(tokens_);
}

void Lexer::lexToken() {
    char c = text_[pos_];
    char next = pos_ + 1 < text_.size() ? text_[pos_ + 1] : '\0';
    if (c == '\n') {
        push(TokenKind::Newline, pos_, 1);
        ++pos_;
        ++line_;
        lineStart_ = pos_;
    } else if (c == ' ' || c == '\t' || c == '\r') {
        ++pos_;
    } else if (c == '#') {
        if (colourContext() && isHex(next)) {
            lexColour();
        } else {
            lexLineComment();
        }
    } else if (c == '/' && next == '/') {
        lexLineComment();
    } else if (c == '/' && next == '*') {
        lexBlockComment();
    } else if (c == '/' && next == '-') {
        push(TokenKind::SlashDash, pos_, 2);
        pos_ += 2;
    } else if (isDigit(c)) {
        if (!lexDateTime()) {
            lexNumber();
        }
    } else if (isIdentStart(c)) {
        std::size_t start = pos_;
        while (pos_ < text_.size() && isIdentChar(text_[pos_])) {
            ++pos_;
        }
        push(TokenKind::Identifier, start, pos_ - start);
    } else if (c == '@') {
        lexReference();
    } else if (c == '"') {
        lexString();
    } else {
        lexPunctuation(c, next);
    }
}

void Lexer::lexLineComment() {
    std::size_t start = pos_;
    while (pos_ < text_.size() && text_[pos_] != '\n') {
        ++pos_;
    }
    if (keepComments_) {
        push(TokenKind::Comment, start, pos_ - start);
    }
}

void Lexer::lexBlockComment() {
    std::size_t start = pos_;
    std::uint32_t startLine = line_;
    std::size_t startLineStart = lineStart_;
    skipBlockComment();
    if (!keepComments_) {
        return;
    }
    // Located at its first line (it may span several), two characters long.
    Token token;
    token.kind = TokenKind::Comment;
    token.text = std::string(text_.substr(start, pos_ - start));
    token.location.file = file_;
    token.location.line = startLine;
    token.location.column = static_cast<std::uint32_t>(start - startLineStart + 1);
    token.location.length = 2;
    token.offset = start;
    token.spaceBefore = start != lastEnd_ || start == startLineStart;
    lastEnd_ = pos_;
    tokens_.push_back(std::move(token));
}

void Lexer::lexReference() {
    std::size_t start = pos_++;
    if (pos_ >= text_.size() || !isIdentStart(text_[pos_])) {
        addError(diagnostics_, "E0004", "expected a name after '@'", locationAt(start, 1),
                 "a reference needs a name: '@height'");
        return;
    }
    std::size_t nameStart = pos_;
    while (pos_ < text_.size() && isIdentChar(text_[pos_])) {
        ++pos_;
    }
    std::string name(text_.substr(nameStart, pos_ - nameStart));
    std::string field;
    // `@ns.name.field`: every dotted part after the first goes into `field`.
    if (pos_ + 1 < text_.size() && text_[pos_] == '.' && isIdentStart(text_[pos_ + 1])) {
        std::size_t fieldStart = ++pos_;
        while (pos_ < text_.size() &&
               (isIdentChar(text_[pos_]) ||
                (text_[pos_] == '.' && pos_ + 1 < text_.size() && isIdentStart(text_[pos_ + 1])))) {
            ++pos_;
        }
        field = std::string(text_.substr(fieldStart, pos_ - fieldStart));
    }
    push(TokenKind::Reference, start, pos_ - start);
    tokens_.back().text = std::move(name);
    tokens_.back().field = std::move(field);
}

void Lexer::lexPunctuation(char c, char next) {
    for (const Punctuation& punctuation : kPunctuation) {
        if (punctuation.first == c && (punctuation.second == '\0' || punctuation.second == next)) {
            const std::size_t length = punctuation.second == '\0' ? 1 : 2;
            push(punctuation.kind, pos_, length);
            pos_ += length;
            return;
        }
    }
    lexUnexpected();
}

void Lexer::lexUnexpected() {
    // A run of unexpected characters is one error, so binary-looking text stays readable.
    std::size_t start = pos_;
    if (text_[pos_] == '&' || text_[pos_] == '|') {
        ++pos_;  // a lone '&' or '|' (the operators are '&&' and '||')
    }
    auto recognised = [](char ch) {
        return ch == '\n' || ch == ' ' || ch == '\t' || ch == '\r' || isIdentChar(ch) ||
               std::string_view("{}[](),=:;+-*/#@\"!<>?%.").find(ch) != std::string_view::npos;
    };
    while (pos_ < text_.size() && !recognised(text_[pos_])) {
        pos_ += std::min(utf8Length(static_cast<unsigned char>(text_[pos_])), text_.size() - pos_);
    }
    std::string run(text_.substr(start, pos_ - start));
    unsigned char first = static_cast<unsigned char>(run[0]);
    std::string shown;
    if (first < 0x20 || first == 0x7F) {
        char buffer[8];
        std::snprintf(buffer, sizeof buffer, "\\x%02X", first);
        shown = buffer;
    } else {
        shown = run.substr(0, utf8Length(first));
    }
    std::string message = run.size() > utf8Length(first) ? "unexpected characters starting with '"
                                                         : "unexpected character '";
    addError(diagnostics_, "E0004", message + shown + "'", locationAt(start, pos_ - start),
             "not part of the language here");
}

void Lexer::lexNumber() {
    std::size_t start = pos_;
    while (pos_ < text_.size() && isDigit(text_[pos_])) {
        ++pos_;
    }
    if (pos_ + 1 < text_.size() && text_[pos_] == '.' && isDigit(text_[pos_ + 1])) {
        ++pos_;
        while (pos_ < text_.size() && isDigit(text_[pos_])) {
            ++pos_;
        }
    }
    if (pos_ < text_.size() && (text_[pos_] == 'e' || text_[pos_] == 'E')) {
        std::size_t look = pos_ + 1;
        if (look < text_.size() && (text_[look] == '+' || text_[look] == '-')) {
            ++look;
        }
        if (look < text_.size() && isDigit(text_[look])) {
            pos_ = look;
            while (pos_ < text_.size() && isDigit(text_[pos_])) {
                ++pos_;
            }
        }
    }
    std::string digits(text_.substr(start, pos_ - start));
    std::size_t unitStart = pos_;
    if (pos_ < text_.size() && text_[pos_] == '%') {
        ++pos_;
    } else {
        while (pos_ < text_.size() && isIdentChar(text_[pos_])) {
            ++pos_;
        }
    }
    std::string unit(text_.substr(unitStart, pos_ - unitStart));
    push(TokenKind::Number, start, pos_ - start);
    Token& token = tokens_.back();
    double value = std::strtod(digits.c_str(), nullptr);
    if (!std::isfinite(value)) {
        addError(diagnostics_, "E0009", "number '" + digits + "' is too large",
                 locationAt(start, pos_ - start), "does not fit in a double");
        value = 0.0;
        token.malformed = true;
    }
    token.number = value;
    if (unit.empty()) {
        return;
    }
    for (const Unit& known : kUnits) {
        if (unit == known.name) {
            token.number = value * known.scale;
            token.dimension = known.dimension;
            return;
        }
    }
    token.malformed = true;
    addError(diagnostics_, "E0008", "unknown unit '" + unit + "'",
             locationAt(unitStart, pos_ - unitStart), "not a unit")
        .help.push_back("units are: m, km, cm, mm, deg, rad, %, px, s, min, h");
}

// Date-times (2024-06-21, 2024-06-21T14:30[:05][Z|+02:00]) and times (14:30[:05]). The
// token text becomes the canonical form with seconds: 2024-06-21T14:30:00+02:00, 14:30:00.
bool Lexer::lexDateTime() {
    auto digitsAt = [&](std::size_t at, std::size_t count) {
        if (at + count > text_.size()) {
            return false;
        }
        for (std::size_t i = 0; i < count; ++i) {
            if (!isDigit(text_[at + i])) {
                return false;
            }
        }
        return true;
    };
    auto valueAt = [&](std::size_t at, std::size_t count) {
        int value = 0;
        for (std::size_t i = 0; i < count; ++i) {
            value = value * 10 + (text_[at + i] - '0');
        }
        return value;
    };
    auto charAt = [&](std::size_t at) { return at < text_.size() ? text_[at] : '\0'; };
    std::size_t start = pos_;
    std::size_t at = pos_;
    std::string canonical;
    bool valid = true;
    // Parses HH:MM[:SS] at `at`; false if it is not there at all.
    auto parseTime = [&](std::size_t hourDigits) {
        int hour = valueAt(at, hourDigits);
        int minute = valueAt(at + hourDigits + 1, 2);
        at += hourDigits + 3;
        int second = 0;
        if (charAt(at) == ':' && digitsAt(at + 1, 2)) {
            second = valueAt(at + 1, 2);
            at += 3;
        }
        valid = valid && hour < 24 && minute < 60 && second < 60;
        char buffer[16];
        std::snprintf(buffer, sizeof buffer, "%02d:%02d:%02d", hour % 100, minute % 100,
                      second % 100);
        canonical += buffer;
    };
    if (digitsAt(at, 4) && charAt(at + 4) == '-' && digitsAt(at + 5, 2) && charAt(at + 7) == '-' &&
        digitsAt(at + 8, 2)) {
        int year = valueAt(at, 4);
        int month = valueAt(at + 5, 2);
        int day = valueAt(at + 8, 2);
        static constexpr int kDays[] = {31, 29, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
        bool leap = (year % 4 == 0 && year % 100 != 0) || year % 400 == 0;
        valid = month >= 1 && month <= 12 && day >= 1 && day <= kDays[month - 1] &&
                (month != 2 || day <= 28 || leap);
        canonical = std::string(text_.substr(at, 10));
        at += 10;
        if (charAt(at) == 'T' && digitsAt(at + 1, 2) && charAt(at + 3) == ':' &&
            digitsAt(at + 4, 2)) {
            ++at;
            canonical += 'T';
            parseTime(2);
            if (charAt(at) == 'Z') {
                canonical += "+00:00";
                ++at;
            } else if ((charAt(at) == '+' || charAt(at) == '-') && digitsAt(at + 1, 2) &&
                       charAt(at + 3) == ':' && digitsAt(at + 4, 2)) {
                valid = valid && valueAt(at + 1, 2) <= 14 && valueAt(at + 4, 2) < 60;
                canonical += std::string(text_.substr(at, 6));
                at += 6;
            }
        }
    } else if (digitsAt(at, 2) && charAt(at + 2) == ':' && digitsAt(at + 3, 2)) {
        parseTime(2);
    } else if (digitsAt(at, 1) && charAt(at + 1) == ':' && digitsAt(at + 2, 2)) {
        parseTime(1);
    } else {
        return false;
    }
    // A date-time glued to letters or digits is not one ("2024-06-21x").
    while (at < text_.size() && isIdentChar(text_[at])) {
        ++at;
        valid = false;
    }
    pos_ = at;
    push(TokenKind::DateTime, start, pos_ - start);
    if (!valid) {
        tokens_.back().malformed = true;
        addError(diagnostics_, "E0009",
                 "invalid date/time '" + std::string(text_.substr(start, pos_ - start)) + "'",
                 locationAt(start, pos_ - start), "expected 2024-06-21T14:30+02:00 or 14:30");
        return true;
    }
    tokens_.back().text = canonical;
    return true;
}

void Lexer::lexColour() {
    std::size_t start = pos_++;
    std::size_t digitsStart = pos_;
    while (pos_ < text_.size() && isIdentChar(text_[pos_])) {
        ++pos_;
    }
    std::string_view digits = text_.substr(digitsStart, pos_ - digitsStart);
    push(TokenKind::Color, start, pos_ - start);
    bool allHex = true;
    for (char ch : digits) {
        allHex = allHex && isHex(ch);
    }
    if (!allHex || (digits.size() != 6 && digits.size() != 8)) {
        tokens_.back().malformed = true;
        addError(diagnostics_, "E0009", "invalid colour '#" + std::string(digits) + "'",
                 locationAt(start, pos_ - start), "expected #RRGGBB or #RRGGBBAA");
        return;
    }
    float components[4] = {0, 0, 0, 1};
    for (std::size_t i = 0; i < digits.size() / 2; ++i) {
        int byte = hexValue(digits[2 * i]) * 16 + hexValue(digits[2 * i + 1]);
        components[i] = static_cast<float>(byte) / 255.0f;
    }
    tokens_.back().color = Color{components[0], components[1], components[2], components[3]};
}

void Lexer::lexString() {
    std::size_t start = pos_++;
    std::string value;
    while (true) {
        if (pos_ >= text_.size() || text_[pos_] == '\n') {
            addError(diagnostics_, "E0005", "unterminated string", locationAt(start, 1),
                     "this string is not closed on its line");
            break;
        }
        char c = text_[pos_];
        if (c == '"') {
            ++pos_;
            break;
        }
        if (c == '\\' && pos_ + 1 < text_.size()) {
            char escaped = text_[pos_ + 1];
            switch (escaped) {
                case '"':
                    value += '"';
                    break;
                case '\\':
                    value += '\\';
                    break;
                case 'n':
                    value += '\n';
                    break;
                case 't':
                    value += '\t';
                    break;
                default:
                    if (escaped == '\n') {
                        addError(diagnostics_, "E0005", "unterminated string", locationAt(start, 1),
                                 "this string is not closed on its line");
                        ++pos_;
                        goto done;
                    }
                    addError(diagnostics_, "E0007",
                             "unknown escape sequence '\\" + std::string(1, escaped) + "'",
                             locationAt(pos_, 2), "valid escapes are \\\" \\\\ \\n \\t");
                    break;
            }
            pos_ += 2;
            continue;
        }
        value += c;
        ++pos_;
    }
done:
    push(TokenKind::String, start, pos_ - start);
    tokens_.back().text = std::move(value);
}

void Lexer::skipBlockComment() {
    SourceLocation opening = locationAt(pos_, 2);
    pos_ += 2;
    int depth = 1;
    while (pos_ < text_.size() && depth > 0) {
        char c = text_[pos_];
        char next = pos_ + 1 < text_.size() ? text_[pos_ + 1] : '\0';
        if (c == '/' && next == '*') {
            ++depth;
            pos_ += 2;
        } else if (c == '*' && next == '/') {
            --depth;
            pos_ += 2;
        } else {
            if (c == '\n') {
                ++line_;
                lineStart_ = pos_ + 1;
            }
            ++pos_;
        }
    }
    if (depth > 0) {
        addError(diagnostics_, "E0006", "unterminated block comment", opening,
                 "this comment is never closed");
    }
}

}  // namespace sylva::dsl
