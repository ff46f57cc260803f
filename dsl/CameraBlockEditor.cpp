#include "sylva/dsl/CameraBlockEditor.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <optional>
#include <sstream>
#include <vector>

#include "sylva/core/base/AtomicFile.h"
#include "sylva/core/scene/CameraNavigation.h"
#include "sylva/dsl/Formatter.h"
#include "sylva/dsl/Lexer.h"

namespace sylva::dsl {
namespace {

constexpr double kDegrees = 180.0 / 3.14159265358979323846;

bool isIdentifier(const std::string& name) {
    if (name.empty() || !(std::isalpha(static_cast<unsigned char>(name[0])) || name[0] == '_')) {
        return false;
    }
    for (char c : name) {
        if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_')) {
            return false;
        }
    }
    return true;
}

// The tokens without newlines (comments are not kept), with their text offsets.
std::vector<Token> tokensOf(std::string_view text, const std::string& displayName) {
    std::vector<Diagnostic> diagnostics;
    Lexer lexer(text, std::make_shared<const std::string>(displayName), diagnostics);
    std::vector<Token> tokens;
    for (Token& token : lexer.tokenize()) {
        if (token.kind != TokenKind::Newline) {
            tokens.push_back(std::move(token));
        }
    }
    return tokens;
}

// Index of the token closing the bracket opened at `open`, or nullopt.
std::optional<std::size_t> matching(const std::vector<Token>& tokens, std::size_t open) {
    int depth = 0;
    for (std::size_t i = open; i < tokens.size(); ++i) {
        const TokenKind kind = tokens[i].kind;
        if (kind == TokenKind::LBrace || kind == TokenKind::LBracket || kind == TokenKind::LParen) {
            ++depth;
        } else if (kind == TokenKind::RBrace || kind == TokenKind::RBracket ||
                   kind == TokenKind::RParen) {
            if (--depth == 0) {
                return i;
            }
        }
    }
    return std::nullopt;
}

// The top-level block `keyword name {`: indices of its keyword and its closing brace.
std::optional<std::pair<std::size_t, std::size_t>> findBlock(const std::vector<Token>& tokens,
                                                             const std::string& keyword,
                                                             const std::string& name) {
    int depth = 0;
    for (std::size_t i = 0; i + 2 < tokens.size(); ++i) {
        const TokenKind kind = tokens[i].kind;
        if (depth == 0 && kind == TokenKind::Identifier && tokens[i].text == keyword &&
            tokens[i + 1].kind == TokenKind::Identifier && tokens[i + 1].text == name &&
            tokens[i + 2].kind == TokenKind::LBrace) {
            std::optional<std::size_t> close = matching(tokens, i + 2);
            if (close) {
                return std::make_pair(i, *close);
            }
            return std::nullopt;
        }
        if (kind == TokenKind::LBrace || kind == TokenKind::LBracket || kind == TokenKind::LParen) {
            ++depth;
        } else if (kind == TokenKind::RBrace || kind == TokenKind::RBracket ||
                   kind == TokenKind::RParen) {
            --depth;
        }
    }
    return std::nullopt;
}

// `text` with `@name` in the cameras list of views block `views`; nullopt when there is
// no such block.
std::optional<std::string> listedInViews(const std::string& text, const std::string& displayName,
                                         const std::string& name, const std::string& views) {
    const std::vector<Token> tokens = tokensOf(text, displayName);
    const auto block = findBlock(tokens, "views", views);
    if (!block) {
        return std::nullopt;
    }
    for (std::size_t i = block->first + 3; i + 2 < block->second; ++i) {
        if (tokens[i].kind != TokenKind::Identifier || tokens[i].text != "cameras" ||
            tokens[i + 1].kind != TokenKind::Equals || tokens[i + 2].kind != TokenKind::LBracket) {
            continue;
        }
        const std::optional<std::size_t> close = matching(tokens, i + 2);
        if (!close) {
            break;
        }
        for (std::size_t j = i + 3; j < *close; ++j) {
            if (tokens[j].kind == TokenKind::Reference && tokens[j].text == name) {
                return text;  // already listed
            }
        }
        const bool empty = *close == i + 3;
        const std::string insert = (empty ? "@" : ", @") + name;
        return text.substr(0, tokens[*close].offset) + insert + text.substr(tokens[*close].offset);
    }
    const std::size_t brace = tokens[block->second].offset;
    return text.substr(0, brace) + "\n    cameras = [@" + name + "]\n" + text.substr(brace);
}

Result<std::string> readText(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    if (!in) {
        return Error{file.string() + ": cannot read the project file"};
    }
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

}  // namespace

std::string CameraBlockEditor::blockText(const std::string& name, const Camera& camera) {
    const CameraAngles angles = CameraNavigation::anglesOf(camera);
    char buffer[512];
    std::snprintf(
        buffer, sizeof buffer,
        "camera %s {\n"
        "    position = geo(%.10fdeg, %.10fdeg, %.4fm)\n"
        "    heading = %.8fdeg\n"
        "    pitch = %.8fdeg\n"
        "    roll = %.8fdeg\n"
        "    fov = %.8fdeg\n"
        "}\n",
        name.c_str(), camera.geodetic.latitude * kDegrees,
        std::remainder(camera.geodetic.longitude, 2.0 * 3.14159265358979323846) * kDegrees,
        camera.geodetic.height, angles.heading * kDegrees, angles.pitch * kDegrees,
        angles.roll * kDegrees, camera.verticalFov * kDegrees);
    return buffer;
}

Result<std::string> CameraBlockEditor::withCamera(std::string_view text,
                                                  const std::string& displayName,
                                                  const std::string& name, const Camera& camera,
                                                  const std::string& views) {
    if (!isIdentifier(name)) {
        return Error{displayName + ": '" + name +
                     "' is not a valid camera name (letters, digits, _)"};
    }
    std::string edited(text);
    const std::vector<Token> tokens = tokensOf(edited, displayName);
    const std::string block = blockText(name, camera);
    if (const auto existing = findBlock(tokens, "camera", name)) {
        const std::size_t begin = tokens[existing->first].offset;
        const std::size_t end = tokens[existing->second].offset + 1;
        edited = edited.substr(0, begin) + block + edited.substr(end);
    } else {
        if (!edited.empty() && edited.back() != '\n') {
            edited += '\n';
        }
        edited += "\n" + block;
    }
    if (!views.empty()) {
        std::optional<std::string> listed = listedInViews(edited, displayName, name, views);
        if (!listed) {
            return Error{displayName + ": no views block '" + views + "' to list camera '" + name +
                         "' in"};
        }
        edited = std::move(*listed);
    }
    SourceFiles sources;
    std::vector<Diagnostic> diagnostics;
    std::optional<std::string> formatted =
        Formatter::format(edited, displayName, sources, diagnostics);
    if (!formatted) {
        std::string reason = diagnostics.empty() ? "syntax errors" : diagnostics.front().message;
        if (!diagnostics.empty() && diagnostics.front().location.valid()) {
            reason = diagnostics.front().location.toString() + ": " + reason;
        }
        return Error{displayName + ": cannot save camera '" + name +
                     "': the project text does not format (" + reason + ")"};
    }
    return *formatted;
}

Status CameraBlockEditor::save(const std::filesystem::path& file, const std::string& name,
                               const Camera& camera, const std::string& views) {
    Result<std::string> text = readText(file);
    if (!text) {
        return text.error();
    }
    Result<std::string> edited = withCamera(text.value(), file.string(), name, camera, views);
    if (!edited) {
        return edited.error();
    }
    if (Status written = writeFileAtomically(file, edited.value()); !written) {
        return Error{file.string() + ": cannot write the project file: " + written.error().message};
    }
    return {};
}

}  // namespace sylva::dsl
