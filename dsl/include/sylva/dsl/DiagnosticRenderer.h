// Renders diagnostics as text in the shape documented in DSL.md:
//
//   error[E0201]: unknown reference '@ground_gradd'
//     --> projects/olinda/olinda.sylva:42:15
//      |
//   42 |     input = @ground_gradd
//      |             ^^^^^^^^^^^^^ no source named 'ground_gradd'
//      = help: did you mean '@ground_graded' (defined at olinda.sylva:17:8)?
//
// A diagnostic without a valid location is rendered as its header line plus notes/help.
#pragma once

#include <string>
#include <vector>

#include "sylva/dsl/Diagnostic.h"
#include "sylva/dsl/SourceFiles.h"

namespace sylva::dsl {

class DiagnosticRenderer {
public:
    explicit DiagnosticRenderer(const SourceFiles& sources) : sources_(sources) {}

    // One diagnostic, every line ending in '\n'. colour=true adds ANSI escape codes.
    std::string render(const Diagnostic& diagnostic, bool colour = false) const;
    // All diagnostics, separated by blank lines.
    std::string render(const std::vector<Diagnostic>& diagnostics, bool colour = false) const;

private:
    const SourceFiles& sources_;
};

}  // namespace sylva::dsl
