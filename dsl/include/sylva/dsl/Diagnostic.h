// Diagnostics of the project language: errors, warnings and notes with stable codes
// (E00xx file/lexical, E01xx syntax, E02xx names, E03xx graph, E04xx values, W0xxx
// warnings) and source locations, rendered by DiagnosticRenderer.
#pragma once

#include <string>
#include <vector>

#include "sylva/core/base/SourceLocation.h"

namespace sylva::dsl {

enum class Severity { Error, Warning, Note };

struct DiagnosticNote {
    std::string message;
    SourceLocation location;  // may be invalid: the note is then shown without "at ..."
};

struct Diagnostic {
    Severity severity = Severity::Error;
    std::string code;         // "E0201", "W0101" ...
    std::string message;      // "unknown reference '@ground_gradd'"
    SourceLocation location;  // primary location; invalid for file-level problems
    std::string label;        // text after the carets
    std::vector<DiagnosticNote> notes;
    std::vector<std::string> help;
    // For cycles: "relief -> detail -> relief", rendered as "= cycle: ..." (DSL.md).
    std::string cycle;
};

// Appends an error / a warning and returns it so callers can add notes and help lines.
Diagnostic& addError(std::vector<Diagnostic>& diagnostics, std::string code, std::string message,
                     SourceLocation location, std::string label = {});
Diagnostic& addWarning(std::vector<Diagnostic>& diagnostics, std::string code, std::string message,
                       SourceLocation location, std::string label = {});
bool hasErrors(const std::vector<Diagnostic>& diagnostics);

// "file:line:col" with the file shortened to its last path component, as used in
// notes and help lines ("defined at olinda.sylva:17:8").
std::string shortLocation(const SourceLocation& location);

}  // namespace sylva::dsl
