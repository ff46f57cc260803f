// A position in a project file, for located diagnostics (file:line:col, 1-based).
#pragma once

#include <cstdint>
#include <memory>
#include <string>

namespace sylva {

struct SourceLocation {
    std::shared_ptr<const std::string>
        file;                  // path as the user should see it; shared, never null once set
    std::uint32_t line = 0;    // 1-based; 0 means "no location"
    std::uint32_t column = 0;  // 1-based, in bytes
    std::uint32_t length = 0;  // bytes covered by the construct (for carets)

    bool valid() const { return file && line > 0; }
    // "file:line:col", or "<unknown>" when there is no location.
    std::string toString() const {
        if (!valid()) {
            return "<unknown>";
        }
        return *file + ":" + std::to_string(line) + ":" + std::to_string(column);
    }
};

}  // namespace sylva
