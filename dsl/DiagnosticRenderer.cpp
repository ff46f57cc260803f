#include "sylva/dsl/DiagnosticRenderer.h"

#include <algorithm>

namespace sylva::dsl {

namespace {

bool isContinuationByte(char c) {
    return (static_cast<unsigned char>(c) & 0xC0) == 0x80;
}

// Carets are counted in characters, not bytes, so they line up under UTF-8 text.
std::size_t countCharacters(std::string_view text) {
    std::size_t count = 0;
    for (char c : text) {
        if (!isContinuationByte(c)) {
            ++count;
        }
    }
    return count;
}

const char* severityName(Severity severity) {
    switch (severity) {
        case Severity::Error:
            return "error";
        case Severity::Warning:
            return "warning";
        case Severity::Note:
            return "note";
    }
    return "error";
}

const char* severityColour(Severity severity) {
    switch (severity) {
        case Severity::Error:
            return "\x1b[1;31m";
        case Severity::Warning:
            return "\x1b[1;33m";
        case Severity::Note:
            return "\x1b[1;36m";
    }
    return "";
}

}  // namespace

std::string DiagnosticRenderer::render(const Diagnostic& diagnostic, bool colour) const {
    const std::string reset = colour ? "\x1b[0m" : "";
    const std::string bold = colour ? "\x1b[1m" : "";
    const std::string blue = colour ? "\x1b[1;34m" : "";
    const std::string accent = colour ? severityColour(diagnostic.severity) : "";

    std::string out;
    out += accent + severityName(diagnostic.severity);
    if (!diagnostic.code.empty()) {
        out += "[" + diagnostic.code + "]";
    }
    out += reset + bold + ": " + diagnostic.message + reset + "\n";

    const SourceLocation& location = diagnostic.location;
    std::string gutter = "  ";
    if (location.valid()) {
        std::string number = std::to_string(location.line);
        std::string pad(number.size(), ' ');
        gutter = pad + " ";
        out += pad + blue + "--> " + reset + location.toString() + "\n";
        out += gutter + blue + "|" + reset + "\n";
        std::string_view line = sources_.line(location.file, location.line);
        out += blue + number + " |" + reset + (line.empty() ? "" : " ") + std::string(line) + "\n";
        std::size_t start = std::min<std::size_t>(location.column - 1, line.size());
        std::size_t end = std::min<std::size_t>(start + location.length, line.size());
        std::string padding;
        for (std::size_t i = 0; i < start; ++i) {
            if (line[i] == '\t') {
                padding += '\t';
            } else if (!isContinuationByte(line[i])) {
                padding += ' ';
            }
        }
        std::size_t carets =
            std::max<std::size_t>(1, countCharacters(line.substr(start, end - start)));
        out += gutter + blue + "|" + reset + " " + padding + accent + std::string(carets, '^');
        if (!diagnostic.label.empty()) {
            out += " " + diagnostic.label;
        }
        out += reset + "\n";
    }
    for (const DiagnosticNote& note : diagnostic.notes) {
        out += bold + "note" + reset + ": " + note.message;
        if (note.location.valid()) {
            out += " at " + shortLocation(note.location);
        }
        out += "\n";
    }
    if (!diagnostic.cycle.empty()) {
        out += gutter + blue + "=" + reset + " " + bold + "cycle" + reset + ": " +
               diagnostic.cycle + "\n";
    }
    for (const std::string& help : diagnostic.help) {
        out += gutter + blue + "=" + reset + " " + bold + "help" + reset + ": " + help + "\n";
    }
    return out;
}

std::string DiagnosticRenderer::render(const std::vector<Diagnostic>& diagnostics,
                                       bool colour) const {
    std::string out;
    for (std::size_t i = 0; i < diagnostics.size(); ++i) {
        if (i > 0) {
            out += "\n";
        }
        out += render(diagnostics[i], colour);
    }
    return out;
}

}  // namespace sylva::dsl
