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

std::string invalidUtf8Message(const std::string& text, std::size_t invalid) {
    std::size_t lineStart = text.rfind('\n', invalid == 0 ? 0 : invalid - 1);
    lineStart = (lineStart == std::string::npos || invalid == 0) ? 0 : lineStart + 1;
    std::size_t line =
        1 + static_cast<std::size_t>(std::count(
                text.begin(), text.begin() + static_cast<std::ptrdiff_t>(invalid), '\n'));
    char byte[8];
    std::snprintf(byte, sizeof byte, "0x%02X", static_cast<unsigned char>(text[invalid]));
    return std::string("not valid UTF-8 (byte ") + byte + " at line " + std::to_string(line) +
           ", column " + std::to_string(invalid - lineStart + 1) + ")";
}

// Follows imports depth-first and collects every parsed file as a unit with its scope.
class ImportWalker {
public:
    ImportWalker(const LoadOptions& options, SourceFiles& sources,
                 std::vector<Diagnostic>& diagnostics)
        : options_(options), sources_(sources), diagnostics_(diagnostics) {}

    void parse(std::string text, const std::string& displayName, const std::filesystem::path& path,
               const std::string& scope) {
        totalBytes_ += text.size();
        std::shared_ptr<const std::string> file = sources_.add(displayName, std::move(text));
        std::vector<Token> tokens = Lexer(sources_.text(file), file, diagnostics_).tokenize();
        asts_.push_back(
            std::make_unique<FileNode>(Parser(std::move(tokens), diagnostics_).parseFile()));
        const FileNode& ast = *asts_.back();
        units_.push_back({&ast, scope});
        files_.push_back(path);
        stack_.push_back({key(path), displayName});
        for (const Statement& statement : ast.statements) {
            if (const auto* import = std::get_if<ImportNode>(&statement)) {
                follow(*import, path, displayName, scope);
            }
        }
        stack_.pop_back();
    }

    std::vector<ParsedUnit> units() const { return units_; }
    std::vector<std::filesystem::path> files() const { return files_; }

private:
    static std::string key(const std::filesystem::path& path) {
        std::error_code error;
        std::filesystem::path canonical = std::filesystem::weakly_canonical(path, error);
        return (error ? path.lexically_normal() : canonical).string();
    }

    void follow(const ImportNode& import, const std::filesystem::path& importer,
                const std::string& importerDisplay, const std::string& scope) {
        const std::filesystem::path path = importer.parent_path() / import.path;
        const std::string display =
            (std::filesystem::path(importerDisplay).parent_path() / import.path)
                .lexically_normal()
                .string();
        const std::string what = "cannot import '" + import.path + "'";
        const std::string childKey = key(path);
        for (std::size_t i = 0; i < stack_.size(); ++i) {
            if (stack_[i].first != childKey) {
                continue;
            }
            std::string chain;
            for (std::size_t k = i; k < stack_.size(); ++k) {
                chain += std::filesystem::path(stack_[k].second).filename().string() + " -> ";
            }
            chain += std::filesystem::path(display).filename().string();
            std::string label = "'";
            label += std::filesystem::path(importerDisplay).filename().string();
            label += "' imports '";
            label += import.path;
            label += "' here, which is already being imported";
            addError(diagnostics_, "E0011", "import cycle", import.pathLocation, label).cycle =
                chain;
            return;
        }
        if (++imports_ > options_.maxImports) {
            if (imports_ == options_.maxImports + 1) {
                addError(diagnostics_, "E0012", "too many imports", import.pathLocation,
                         "a project may import at most " + std::to_string(options_.maxImports) +
                             " files");
            }
            return;
        }
        std::error_code error;
        std::filesystem::file_status status = std::filesystem::status(path, error);
        if (error || !std::filesystem::exists(status)) {
            addError(diagnostics_, "E0001", what + ": no such file", import.pathLocation,
                     "looked for '" + display + "'")
                .help.push_back("import paths are relative to the file that writes them");
            return;
        }
        if (std::filesystem::is_directory(status)) {
            addError(diagnostics_, "E0001", what + ": it is a directory", import.pathLocation,
                     "'" + display + "' is a directory");
            return;
        }
        if (!std::filesystem::is_regular_file(status)) {
            // Devices and pipes could block or never end (/dev/zero).
            addError(diagnostics_, "E0001", what + ": not a regular file", import.pathLocation,
                     "'" + display + "' is a device, pipe or socket");
            return;
        }
        std::uintmax_t size = std::filesystem::file_size(path, error);
        if (!error && (size > kMaxProjectFileBytes || totalBytes_ + size > kMaxProjectBytes)) {
            addError(diagnostics_, "E0002", what + ": file too large", import.pathLocation,
                     std::to_string(size) +
                         " bytes; files are limited to 16 MiB and a project "
                         "to 64 MiB");
            return;
        }
        std::ifstream stream(path, std::ios::binary);
        std::string text((std::istreambuf_iterator<char>(stream)),
                         std::istreambuf_iterator<char>());
        if (!stream.good() && !stream.eof()) {
            addError(diagnostics_, "E0001", what + ": read error", import.pathLocation,
                     "could not read '" + display + "'");
            return;
        }
        std::size_t invalid = findInvalidUtf8(text);
        if (invalid != text.size()) {
            addError(diagnostics_, "E0003", what + ": " + invalidUtf8Message(text, invalid),
                     import.pathLocation, "'" + display + "' is not UTF-8 text");
            return;
        }
        parse(std::move(text), display, path,
              import.alias.empty() ? scope : scope + import.alias + ".");
    }

    const LoadOptions& options_;
    SourceFiles& sources_;
    std::vector<Diagnostic>& diagnostics_;
    std::vector<std::unique_ptr<FileNode>> asts_;
    std::vector<ParsedUnit> units_;
    std::vector<std::filesystem::path> files_;
    std::vector<std::pair<std::string, std::string>> stack_;  // key, display name
    std::size_t imports_ = 0;
    std::size_t totalBytes_ = 0;

public:
    // The parsed files must outlive the resolved model's construction.
    std::vector<std::unique_ptr<FileNode>>& asts() { return asts_; }
};

// Parses `name=value` given on the command line as its own one-line "file", so its
// errors get carets too. Returns the value expression (null after a syntax error).
ExprPtr parseCommandLineValue(SourceFiles& sources, std::vector<Diagnostic>& diagnostics,
                              const std::string& prefix, const std::string& name,
                              const std::string& value, SourceLocation& nameLocation) {
    std::string line = prefix + name + "=" + value;
    std::shared_ptr<const std::string> file = sources.add("<command line>", line);
    nameLocation.file = file;
    nameLocation.line = 1;
    nameLocation.column = static_cast<std::uint32_t>(prefix.size() + 1);
    nameLocation.length = static_cast<std::uint32_t>(name.size());
    std::vector<Token> tokens =
        Lexer(sources.text(file), file, diagnostics, prefix.size() + name.size() + 1).tokenize();
    return Parser(std::move(tokens), diagnostics).parseLoneExpression();
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
        return fileError("E0003",
                         "cannot read '" + displayName + "': " + invalidUtf8Message(text, invalid));
    }

    auto sources = std::make_shared<SourceFiles>();
    LoadResult result;
    ImportWalker walker(options, *sources, result.diagnostics);
    walker.parse(std::move(text), displayName, path, "");

    std::vector<DefineNode> defines;
    for (const auto& [name, value] : options.defines) {
        DefineNode define;
        define.name = name;
        define.value = parseCommandLineValue(*sources, result.diagnostics, "-D ", name, value,
                                             define.nameLocation);
        defines.push_back(std::move(define));
    }
    std::vector<SetNode> sets;
    for (const auto& [target, value] : options.sets) {
        SetNode set;
        std::size_t dot = target.rfind('.');
        set.block = dot == std::string::npos ? std::string() : target.substr(0, dot);
        set.attribute.name = dot == std::string::npos ? target : target.substr(dot + 1);
        set.attribute.value = parseCommandLineValue(*sources, result.diagnostics, "--set ", target,
                                                    value, set.attribute.nameLocation);
        if (dot == std::string::npos || set.block.empty() || set.attribute.name.empty()) {
            addError(result.diagnostics, "E0213",
                     "--set needs BLOCK.ATTRIBUTE, found '" + target + "'",
                     set.attribute.nameLocation, "expected e.g. render.exposure");
            continue;
        }
        // The attribute name is the last part of the path.
        set.blockLocation = set.attribute.nameLocation;
        set.blockLocation.length = static_cast<std::uint32_t>(dot);
        set.attribute.nameLocation.column += static_cast<std::uint32_t>(dot + 1);
        set.attribute.nameLocation.length = static_cast<std::uint32_t>(target.size() - dot - 1);
        if (set.attribute.value) {
            sets.push_back(std::move(set));
        }
    }

    // Resolve even after syntax errors, so one run shows every problem.
    ResolveOptions resolveOptions;
    resolveOptions.lenient = options.lenient;
    std::vector<ProjectModel> models =
        Resolver(*options.schema, result.diagnostics)
            .resolve(walker.units(), defines, sets, path, resolveOptions);
    std::stable_sort(result.diagnostics.begin(), result.diagnostics.end(),
                     [&](const Diagnostic& a, const Diagnostic& b) {
                         auto key = [&](const Diagnostic& d) {
                             return std::make_tuple(d.location.valid() ? 1 : 0,
                                                    sources->index(d.location.file),
                                                    d.location.line, d.location.column);
                         };
                         return key(a) < key(b);
                     });
    // A problem inside a block shared by several scenarios is reported once.
    std::vector<Diagnostic> unique;
    for (Diagnostic& diagnostic : result.diagnostics) {
        bool seen = std::any_of(unique.begin(), unique.end(), [&](const Diagnostic& other) {
            return other.code == diagnostic.code && other.message == diagnostic.message &&
                   other.location.file == diagnostic.location.file &&
                   other.location.line == diagnostic.location.line &&
                   other.location.column == diagnostic.location.column;
        });
        if (!seen) {
            unique.push_back(std::move(diagnostic));
        }
    }
    result.diagnostics = std::move(unique);
    if (!hasErrors(result.diagnostics) && !models.empty()) {
        result.model = models.front();
        if (!models.front().scenario.empty()) {
            result.scenarios = std::move(models);
        }
    }
    result.files = walker.files();
    result.sources = std::move(sources);
    return result;
}

}  // namespace

bool LoadResult::hasErrors() const {
    return dsl::hasErrors(diagnostics);
}

const ProjectModel* LoadResult::modelFor(std::string_view name) const {
    for (const ProjectModel& scenario : scenarios) {
        if (scenario.scenario == name) {
            return &scenario;
        }
    }
    if (model && model->scenario == name) {
        return &*model;
    }
    return nullptr;
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
    if (!std::filesystem::is_regular_file(status)) {
        return fileError("E0001", "cannot read '" + display + "': not a regular file");
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
