#include "sylva/render/gl/ShaderLibrary.h"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string_view>
#include <utility>

namespace sylva::render {
namespace {

const std::map<std::string, std::string_view, std::less<>>& embeddedTable() {
    static const auto* table = [] {
        auto* result = new std::map<std::string, std::string_view, std::less<>>();
        for (std::size_t i = 0; i < detail::kEmbeddedShaderCount; ++i) {
            const detail::EmbeddedShader& shader = detail::kEmbeddedShaders[i];
            result->emplace(shader.path, std::string_view(shader.source, shader.size));
        }
        return result;
    }();
    return *table;
}

// "a/./b/../c.glsl" -> "a/c.glsl", always with '/' separators.
std::string normalize(std::string_view path) {
    return std::filesystem::path(path).lexically_normal().generic_string();
}

std::string_view trimLeft(std::string_view text) {
    const std::size_t start = text.find_first_not_of(" \t");
    return start == std::string_view::npos ? std::string_view() : text.substr(start);
}

// For a line starting with `#`, optional blanks and then `name`, returns the rest of the line.
std::optional<std::string_view> directive(std::string_view line, std::string_view name) {
    std::string_view text = trimLeft(line);
    if (text.empty() || text.front() != '#') {
        return std::nullopt;
    }
    text = trimLeft(text.substr(1));
    if (text.substr(0, name.size()) != name) {
        return std::nullopt;
    }
    std::string_view rest = text.substr(name.size());
    if (!rest.empty() && rest.front() != ' ' && rest.front() != '\t' && rest.front() != '"' &&
        rest.front() != '<') {
        return std::nullopt;  // e.g. "#includes"
    }
    return trimLeft(rest);
}

std::vector<std::string_view> splitLines(std::string_view text) {
    std::vector<std::string_view> lines;
    std::size_t start = 0;
    while (start < text.size()) {
        std::size_t end = text.find('\n', start);
        if (end == std::string_view::npos) {
            end = text.size();
        }
        std::string_view line = text.substr(start, end - start);
        if (!line.empty() && line.back() == '\r') {
            line.remove_suffix(1);
        }
        lines.push_back(line);
        start = end + 1;
    }
    return lines;
}

class Preprocessor {
public:
    explicit Preprocessor(const ShaderLibrary& library) : library_(library) {}

    Result<PreprocessedShader> run(const std::string& path, std::string_view defines) {
        Result<std::string> text = library_.load(path);
        if (!text) {
            return text.error();
        }
        const std::vector<std::string_view> lines = splitLines(*text);
        // #version must stay the first line: find it and emit it before anything else.
        std::optional<std::size_t> versionLine;
        for (std::size_t i = 0; i < lines.size(); ++i) {
            if (directive(lines[i], "version")) {
                versionLine = i;
                break;
            }
        }
        if (versionLine) {
            output_ += lines[*versionLine];
            output_ += '\n';
        }
        result_.files.push_back(library_.displayName(path));
        if (!defines.empty()) {
            const int definesIndex = 1;
            result_.files.emplace_back("<defines>");
            output_ += lineDirective(1, definesIndex);
            output_ += defines;
            if (defines.back() != '\n') {
                output_ += '\n';
            }
        }
        output_ += lineDirective(1, 0);
        included_.insert(path);
        if (Status status = processFile(path, 0, lines, versionLine); !status) {
            return status.error();
        }
        result_.source = std::move(output_);
        return std::move(result_);
    }

private:
    static std::string lineDirective(int line, int index) {
        return "#line " + std::to_string(index * PreprocessedShader::kLineStride + line) + " " +
               std::to_string(index) + "\n";
    }

    Status processFile(const std::string& path, int index,
                       const std::vector<std::string_view>& lines,
                       std::optional<std::size_t> skipLine) {
        if (lines.size() >= static_cast<std::size_t>(PreprocessedShader::kLineStride)) {
            return Error{library_.displayName(path) + ": too long for #line mapping (" +
                         std::to_string(lines.size()) + " lines, at most " +
                         std::to_string(PreprocessedShader::kLineStride - 1) + ")"};
        }
        stack_.push_back(path);
        for (std::size_t i = 0; i < lines.size(); ++i) {
            const int lineNumber = static_cast<int>(i) + 1;
            if (skipLine == i || directive(lines[i], "version")) {
                output_ += '\n';  // #version of the main file was hoisted; others are dropped
                continue;
            }
            std::optional<std::string_view> include = directive(lines[i], "include");
            if (!include) {
                output_ += lines[i];
                output_ += '\n';
                continue;
            }
            const std::string where = library_.displayName(path) + ":" + std::to_string(lineNumber);
            Result<std::string> target = resolve(path, *include, where);
            if (!target) {
                return target.error();
            }
            if (std::find(stack_.begin(), stack_.end(), *target) != stack_.end()) {
                std::string chain;
                auto cycleStart = std::find(stack_.begin(), stack_.end(), *target);
                for (auto it = cycleStart; it != stack_.end(); ++it) {
                    chain += library_.displayName(*it) + " -> ";
                }
                chain += library_.displayName(*target);
                return Error{where + ": include cycle: " + chain};
            }
            if (!included_.insert(*target).second) {
                output_ += '\n';  // already included once in this program
                continue;
            }
            Result<std::string> text = library_.load(*target);
            if (!text) {
                return Error{where + ": " + text.error().message};
            }
            const int childIndex = static_cast<int>(result_.files.size());
            result_.files.push_back(library_.displayName(*target));
            output_ += lineDirective(1, childIndex);
            if (Status status = processFile(*target, childIndex, splitLines(*text), std::nullopt);
                !status) {
                return status;
            }
            output_ += lineDirective(lineNumber + 1, index);
        }
        stack_.pop_back();
        return Status::success();
    }

    // Resolves the argument of an #include found at `where` in `includer`.
    Result<std::string> resolve(const std::string& includer, std::string_view argument,
                                const std::string& where) {
        if (argument.empty() || (argument.front() != '"' && argument.front() != '<')) {
            return Error{where + ": malformed #include (expected \"path\" or <path>)"};
        }
        const char close = argument.front() == '"' ? '"' : '>';
        const std::size_t end = argument.find(close, 1);
        if (end == std::string_view::npos || end == 1) {
            return Error{where + ": malformed #include (expected \"path\" or <path>)"};
        }
        const std::string_view name = argument.substr(1, end - 1);
        std::vector<std::string> candidates;
        if (close == '"') {
            const std::string folder =
                std::filesystem::path(includer).parent_path().generic_string();
            if (!folder.empty()) {
                candidates.push_back(normalize(folder + "/" + std::string(name)));
            }
        }
        const std::string fromRoot = normalize(name);
        if (std::find(candidates.begin(), candidates.end(), fromRoot) == candidates.end()) {
            candidates.push_back(fromRoot);
        }
        std::string tried;
        for (const std::string& candidate : candidates) {
            if (library_.load(candidate)) {
                return candidate;
            }
            tried += (tried.empty() ? "" : ", ") + library_.displayName(candidate);
        }
        return Error{where + ": cannot find include \"" + std::string(name) + "\" (tried " + tried +
                     ")"};
    }

    const ShaderLibrary& library_;
    PreprocessedShader result_;
    std::string output_;
    std::vector<std::string> stack_;
    std::set<std::string> included_;
};

}  // namespace

std::string PreprocessedShader::translateLog(std::string_view log) const {
    // Mesa "0:12(3): error", NVIDIA "0(12) : error", AMD "ERROR: 0:12: error". The
    // source-string number is ignored (Mesa often reports 0): the line encodes the file.
    static const std::regex kMesa(R"(^(\d+):(\d+)\(\d+\): ?(.*)$)");
    static const std::regex kNvidia(R"(^(\d+)\((\d+)\) ?: ?(.*)$)");
    static const std::regex kAmd(R"(^(ERROR|WARNING): (\d+):(\d+): ?(.*)$)");
    // "<file>:<line>" for an emitted GLSL line number, or nullopt for unknown files.
    auto location = [this](const std::string& glslLine) -> std::optional<std::string> {
        const unsigned long long value = std::stoull(glslLine);
        const unsigned long long index = value / kLineStride;
        if (glslLine.size() > 18 || index >= files.size()) {
            return std::nullopt;
        }
        return files[index] + ":" + std::to_string(value % kLineStride);
    };
    std::string result;
    for (std::string_view lineView : splitLines(log)) {
        const std::string line(lineView);
        std::smatch match;
        std::string translated = line;
        if (std::regex_match(line, match, kMesa) || std::regex_match(line, match, kNvidia)) {
            if (std::optional<std::string> where = location(match[2].str())) {
                translated = *where + ": " + match[3].str();
            }
        } else if (std::regex_match(line, match, kAmd)) {
            if (std::optional<std::string> where = location(match[3].str())) {
                translated = match[1].str() + ": " + *where + ": " + match[4].str();
            }
        }
        result += translated;
        result += '\n';
    }
    return result;
}

ShaderLibrary::ShaderLibrary(std::optional<std::filesystem::path> directory)
    : directory_(std::move(directory)) {}

ShaderLibrary::ShaderLibrary() {
    const char* directory = std::getenv("SYLVA_SHADER_DIR");
    if (directory != nullptr && directory[0] != '\0') {
        directory_ = std::filesystem::path(directory);
    }
}

ShaderLibrary ShaderLibrary::embedded() {
    return ShaderLibrary(std::nullopt);
}

ShaderLibrary ShaderLibrary::fromDirectory(std::filesystem::path directory) {
    return ShaderLibrary(std::optional<std::filesystem::path>(std::move(directory)));
}

std::string ShaderLibrary::displayName(std::string_view path) const {
    if (directory_) {
        return (*directory_ / std::filesystem::path(path)).lexically_normal().string();
    }
    return "shaders/" + std::string(path);
}

Result<std::string> ShaderLibrary::load(std::string_view path) const {
    const std::string normalized = normalize(path);
    for (const auto& [extraPath, source] : extra_) {
        if (extraPath == normalized) {
            return std::string(source);
        }
    }
    if (directory_) {
        std::ifstream stream(*directory_ / normalized, std::ios::binary);
        if (!stream) {
            return Error{"shader file not found: " + displayName(normalized)};
        }
        return std::string(std::istreambuf_iterator<char>(stream),
                           std::istreambuf_iterator<char>());
    }
    const auto& table = embeddedTable();
    const auto found = table.find(normalized);
    if (found == table.end()) {
        return Error{"shader file not found: " + displayName(normalized) +
                     " (not embedded; rebuild after adding shaders, or set SYLVA_SHADER_DIR)"};
    }
    return std::string(found->second);
}

Result<PreprocessedShader> ShaderLibrary::preprocessWithMap(std::string_view path,
                                                            std::string_view defines) const {
    return Preprocessor(*this).run(normalize(path), defines);
}

Result<std::string> ShaderLibrary::preprocess(std::string_view path,
                                              std::string_view defines) const {
    Result<PreprocessedShader> result = preprocessWithMap(path, defines);
    if (!result) {
        return result.error();
    }
    return std::move(result->source);
}

ShaderLibrary ShaderLibrary::withEmbedded(const detail::EmbeddedShader* table,
                                          std::size_t count) const {
    ShaderLibrary copy = *this;
    for (std::size_t i = 0; i < count; ++i) {
        copy.extra_.emplace_back(normalize(table[i].path),
                                 std::string_view(table[i].source, table[i].size));
    }
    return copy;
}

std::vector<std::string> ShaderLibrary::embeddedPaths() {
    std::vector<std::string> paths;
    for (const auto& [path, source] : embeddedTable()) {
        paths.push_back(path);
    }
    return paths;
}

}  // namespace sylva::render
