// The texts the loader read (project files and -D values), kept so diagnostics can
// show source lines long after parsing. Files are identified by the shared name
// pointer stored in every SourceLocation, so two files may share a display name.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "sylva/core/base/SourceLocation.h"

namespace sylva::dsl {

class SourceFiles {
public:
    // Stores `text` under `displayName`; the returned pointer goes into SourceLocation::file.
    std::shared_ptr<const std::string> add(std::string displayName, std::string text);
    // The text of a registered file; empty if `file` was not registered here.
    std::string_view text(const std::shared_ptr<const std::string>& file) const;
    // Line `line` (1-based) of `file` without its line ending; empty if out of range.
    std::string_view line(const std::shared_ptr<const std::string>& file, std::uint32_t line) const;
    // Registration order of `file` (for sorting diagnostics); files_.size() if unknown.
    std::size_t index(const std::shared_ptr<const std::string>& file) const;

private:
    struct File {
        std::shared_ptr<const std::string> name;
        std::string text;
        std::vector<std::size_t> lineStarts;
    };
    const File* find(const std::shared_ptr<const std::string>& file) const;
    std::vector<std::unique_ptr<File>> files_;
};

}  // namespace sylva::dsl
