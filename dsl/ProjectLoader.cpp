#include "sylva/dsl/ProjectLoader.h"

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <system_error>
#include <tuple>

#include "sylva/dsl/DiagnosticRenderer.h"
#include "sylva/dsl/Lexer.h"
#include "sylva/dsl/Parser.h"
#include "sylva/dsl/Resolver.h"

namespace sylva::dsl {

namespace {

// Offset of the first invalid UTF-8 byte, or text.size() if the text is valid.
std::size_t findInvalidUtf8(std::string_view text) {
    std::size_t i = 0;
    while (i < text.size()) {
        unsigned char c = static_cast<unsigned char>(text[i]);
        std::size_t length = 0;
        std::uint32_t minimum = 0;
        std::uint32_t codePoint = 0;
        if (c < 0x80) {
            ++i;
            continue;
        } else if ((c & 0xE0) == 0xC0) {
            length = 2;
            minimum = 0x80;
            codePoint = c & 0x1F;
        } else if ((c & 0xF0) == 0xE0) {
            length = 3;
            minimum = 0x800;
            codePoint = c & 0x0F;
        } else if ((c & 0xF8) == 0xF0) {
            length = 4;
            minimum = 0x10000;
            codePoint = c & 0x07;
        } else {
            return i;
        }
        if (i + length > text.size()) {
            return i;
        }
        for (std::size_t k = 1; k < length; ++k) {
            unsigned char continuation = static_cast<unsigned char>(text[i + k]);
            if ((continuation & 0xC0) != 0x80) {
                return i;
            }
            codePoint = (codePoint << 6) | (continuation & 0x3F);
        }
        // Overlong forms, surrogates and values past U+10FFFF are not UTF-8.
        if (codePoint < minimum || codePoint > 0x10FFFF ||
            (codePoint >= 0xD800 && codePoint <= 0xDFFF)) {
            return i;
        }
        i += length;
    }
    return text.size();
}

LoadResult fileError(std::string code, std::string message) {
    LoadResult result;
    result.sources = std::make_shared<SourceFiles>();
    addError(result.diagnostics, std::move(code), std::move(message), {});
    return result;
}

LoadResult loadText(std::string text, const std::string& displayName,
                    const std::filesystem::path& path, const LoadOptions& options) {
    if (text.size() > kMaxProjectFileBytes) {
        return fileError("E0002", "cannot read '" + displayName + "': file is " +
                                      std::to_string(text.size()) +
                                      " bytes, over the 16 MiB limit");
    }
    std::size_t invalid = findInvalidUtf8(text);
    if (invalid != text.size()) {
        std::size_t lineStart = text.rfind('\n', invalid == 0 ? 0 : invalid - 1);
        lineStart = (lineStart == std::string::npos || invalid == 0) ? 0 : lineStart + 1;
        std::size_t line =
            1 + static_cast<std::size_t>(std::count(
                    text.begin(), text.begin() + static_cast<std::ptrdiff_t>(invalid), '\n'));
        char byte[8];
        std::snprintf(byte, sizeof byte, "0x%02X", static_cast<unsigned char>(text[invalid]));
        return fileError("E0003", "cannot read '" + displayName + "': not valid UTF-8 (byte " +
                                      byte + " at line " + std::to_string(line) + ", column " +
                                      std::to_string(invalid - lineStart + 1) + ")");
    }

    auto sources = std::make_shared<SourceFiles>();
    LoadResult result;
    std::shared_ptr<const std::string> file = sources->add(displayName, std::move(text));
    std::vector<Token> tokens = Lexer(sources->text(file), file, result.diagnostics).tokenize();
    FileNode ast = Parser(std::move(tokens), result.diagnostics).parseFile();

    std::vector<DefineNode> defines;
    for (const auto& [name, value] : options.defines) {
        // Each -D is shown as its own one-line "file", so its errors get carets too.
        std::string line = "-D " + name + "=" + value;
        std::shared_ptr<const std::string> defineFile = sources->add("<command line>", line);
        DefineNode define;
        define.name = name;
        define.nameLocation.file = defineFile;
        define.nameLocation.line = 1;
        define.nameLocation.column = 4;
        define.nameLocation.length = static_cast<std::uint32_t>(name.size());
        std::vector<Token> valueTokens =
            Lexer(sources->text(defineFile), defineFile, result.diagnostics, 4 + name.size())
                .tokenize();
        define.value = Parser(std::move(valueTokens), result.diagnostics).parseLoneExpression();
        defines.push_back(std::move(define));
    }

    // Resolve even after syntax errors, so one run shows every problem.
    std::optional<ProjectModel> model =
        Resolver(*options.schema, result.diagnostics).resolve(ast, defines, path);
    std::stable_sort(result.diagnostics.begin(), result.diagnostics.end(),
                     [&](const Diagnostic& a, const Diagnostic& b) {
                         auto key = [&](const Diagnostic& d) {
                             return std::make_tuple(d.location.valid() ? 1 : 0,
                                                    sources->index(d.location.file),
                                                    d.location.line, d.location.column);
                         };
                         return key(a) < key(b);
                     });
    if (!hasErrors(result.diagnostics)) {
        result.model = std::move(model);
    }
    result.sources = std::move(sources);
    return result;
}

}  // namespace

bool LoadResult::hasErrors() const {
    return dsl::hasErrors(diagnostics);
}

std::string LoadResult::render(bool colour) const {
    static const SourceFiles kEmpty;
    return DiagnosticRenderer(sources ? *sources : kEmpty).render(diagnostics, colour);
}

LoadResult loadProject(const std::filesystem::path& file, const LoadOptions& options) {
    const std::string display = file.string();
    std::error_code error;
    std::filesystem::file_status status = std::filesystem::status(file, error);
    if (error || !std::filesystem::exists(status)) {
        return fileError("E0001", "cannot read '" + display + "': no such file");
    }
    if (std::filesystem::is_directory(status)) {
        return fileError("E0001", "cannot read '" + display + "': it is a directory");
    }
    std::uintmax_t size = std::filesystem::file_size(file, error);
    if (!error && size > kMaxProjectFileBytes) {
        return fileError("E0002", "cannot read '" + display + "': file is " + std::to_string(size) +
                                      " bytes, over the 16 MiB limit");
    }
    std::ifstream stream(file, std::ios::binary);
    if (!stream) {
        return fileError("E0001", "cannot read '" + display + "': " + std::strerror(errno));
    }
    std::string text((std::istreambuf_iterator<char>(stream)), std::istreambuf_iterator<char>());
    if (stream.bad()) {
        return fileError("E0001", "cannot read '" + display + "': read error");
    }
    return loadText(std::move(text), display, file, options);
}

LoadResult loadProjectFromString(std::string_view text, const std::string& displayName,
                                 const LoadOptions& options) {
    return loadText(std::string(text), displayName, displayName, options);
}

}  // namespace sylva::dsl
