// libFuzzer target for the project language: any bytes must load or yield located
// diagnostics (file-level problems excepted), render without crashing, and, when the
// text formats, formatting must be idempotent and keep the text loadable the same way.
//
//   CC=clang CXX=clang++ cmake -S . -B build-fuzz -G Ninja -DSYLVA_FUZZ=ON
//   cmake --build build-fuzz --target sylva_dsl_fuzz
//   build-fuzz/tests/dsl/fuzz/sylva_dsl_fuzz tests/dsl/fuzz-corpus -max_total_time=600
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

#include "sylva/dsl/Formatter.h"
#include "sylva/dsl/ProjectLoader.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace sylva::dsl;
    const std::string_view text(reinterpret_cast<const char*>(data), size);
    LoadOptions options;
    options.maxImports = 2;  // imports resolve against the working directory
    LoadResult result = loadProjectFromString(text, "fuzz.sylva", options);
    for (const Diagnostic& diagnostic : result.diagnostics) {
        bool fileLevel = diagnostic.code == "E0002" || diagnostic.code == "E0003";
        if (!diagnostic.location.valid() && !fileLevel) {
            std::abort();
        }
    }
    if (result.hasErrors() == result.model.has_value()) {
        std::abort();
    }
    (void)result.render();

    SourceFiles sources;
    std::vector<Diagnostic> diagnostics;
    std::optional<std::string> once = Formatter::format(text, "fuzz.sylva", sources, diagnostics);
    if (once) {
        std::optional<std::string> twice =
            Formatter::format(*once, "fuzz.sylva", sources, diagnostics);
        if (!twice || *twice != *once) {
            std::abort();  // fmt must be idempotent
        }
        LoadResult reformatted = loadProjectFromString(*once, "fuzz.sylva", options);
        if (reformatted.hasErrors() != result.hasErrors() ||
            reformatted.diagnostics.size() != result.diagnostics.size()) {
            std::abort();  // fmt must not change what the text means
        }
    }
    return 0;
}
