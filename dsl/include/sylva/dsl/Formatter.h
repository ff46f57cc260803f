// `sylva fmt`: canonical layout of project text. Works on the token stream (with
// comments), so every comment survives and the result parses to the same syntax tree:
// 4-space indentation by open brackets, single spaces between tokens, no space inside
// () and [], at most one blank line, no trailing whitespace, one final newline.
// Text with lexical or syntax errors is not formatted (the diagnostics say why).
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "sylva/dsl/Diagnostic.h"
#include "sylva/dsl/SourceFiles.h"

namespace sylva::dsl {

class Formatter {
public:
    // The canonical text, or nullopt after appending the errors that prevent formatting.
    // `sources` receives the text so diagnostics can be rendered.
    static std::optional<std::string> format(std::string_view text, const std::string& displayName,
                                             SourceFiles& sources,
                                             std::vector<Diagnostic>& diagnostics);
};

}  // namespace sylva::dsl
