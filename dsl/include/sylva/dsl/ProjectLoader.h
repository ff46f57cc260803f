// Entry point of the project language: reads a `.sylva` file, runs lexer -> parser ->
// resolver and returns the ProjectModel together with every diagnostic. Never throws;
// every failure (missing file, bad UTF-8, syntax, names, types) is a diagnostic.
#pragma once

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "sylva/core/model/ProjectModel.h"
#include "sylva/core/model/Schema.h"
#include "sylva/dsl/Diagnostic.h"
#include "sylva/dsl/SourceFiles.h"

namespace sylva::dsl {

// Project files above this size are refused (E0002), in bytes.
inline constexpr std::size_t kMaxProjectFileBytes = 16u * 1024u * 1024u;

// Files one project may import, directly or indirectly (E0012).
inline constexpr std::size_t kMaxImports = 256;
// Bytes of all files of one project together (E0002).
inline constexpr std::size_t kMaxProjectBytes = 64u * 1024u * 1024u;

struct LoadOptions {
    // -D name=value: sets declared params only; value parsed with the expression grammar.
    std::vector<std::pair<std::string, std::string>> defines;
    // --set block.attribute=value: any schema attribute, checked like source text.
    std::vector<std::pair<std::string, std::string>> sets;
    bool lenient = false;  // unknown attributes are warnings (W0102) instead of errors
    const SchemaRegistry* schema = &SchemaRegistry::builtin();
    std::size_t maxImports = kMaxImports;
};

struct LoadResult {
    std::optional<ProjectModel> model;           // the first scenario; present iff no errors
    std::vector<ProjectModel> scenarios;         // one model per scenario (same order)
    std::vector<Diagnostic> diagnostics;         // errors and warnings, in source order
    std::shared_ptr<const SourceFiles> sources;  // texts the diagnostics point into
    std::vector<std::filesystem::path> files;    // every project file read (for watching)

    bool hasErrors() const;
    // The model of scenario `name`; nullptr if there is none (or the project has errors).
    const ProjectModel* modelFor(std::string_view name) const;
    // All diagnostics as text in the DSL.md shape; colour=false: no ANSI codes.
    std::string render(bool colour = false) const;
};

// Loads `file`; diagnostics name it as given (relative paths stay relative).
LoadResult loadProject(const std::filesystem::path& file, const LoadOptions& options = {});
// Loads project text held in memory; `displayName` stands for the file in diagnostics.
LoadResult loadProjectFromString(std::string_view text, const std::string& displayName,
                                 const LoadOptions& options = {});

}  // namespace sylva::dsl
