#include "sylva/dsl/Diagnostic.h"

#include <filesystem>
#include <utility>

namespace sylva::dsl {

namespace {
Diagnostic& add(std::vector<Diagnostic>& diagnostics, Severity severity, std::string code,
                std::string message, SourceLocation location, std::string label) {
    Diagnostic diagnostic;
    diagnostic.severity = severity;
    diagnostic.code = std::move(code);
    diagnostic.message = std::move(message);
    diagnostic.location = std::move(location);
    diagnostic.label = std::move(label);
    diagnostics.push_back(std::move(diagnostic));
    return diagnostics.back();
}
}  // namespace

Diagnostic& addError(std::vector<Diagnostic>& diagnostics, std::string code, std::string message,
                     SourceLocation location, std::string label) {
    return add(diagnostics, Severity::Error, std::move(code), std::move(message),
               std::move(location), std::move(label));
}

Diagnostic& addWarning(std::vector<Diagnostic>& diagnostics, std::string code, std::string message,
                       SourceLocation location, std::string label) {
    return add(diagnostics, Severity::Warning, std::move(code), std::move(message),
               std::move(location), std::move(label));
}

bool hasErrors(const std::vector<Diagnostic>& diagnostics) {
    for (const Diagnostic& diagnostic : diagnostics) {
        if (diagnostic.severity == Severity::Error) {
            return true;
        }
    }
    return false;
}

std::string shortLocation(const SourceLocation& location) {
    if (!location.valid()) {
        return "<unknown>";
    }
    std::string name = std::filesystem::path(*location.file).filename().string();
    if (name.empty()) {
        name = *location.file;
    }
    return name + ":" + std::to_string(location.line) + ":" + std::to_string(location.column);
}

}  // namespace sylva::dsl
