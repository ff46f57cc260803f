// BlockReader: typed access to the attributes of a model Block, falling back to the
// schema's defaults for attributes the project did not set. The DSL has already
// checked types and ranges; a value of the wrong type here is a programmer error
// (SYLVA_CHECK), while a missing required value is reported as a Result error so
// models built by hand (tests, examples) fail gracefully.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "sylva/core/base/Result.h"
#include "sylva/core/model/ProjectModel.h"
#include "sylva/core/model/Schema.h"

namespace sylva {

class BlockReader {
public:
    // `schema` may be null (then only explicitly written attributes exist).
    BlockReader(const Block& block, const KindSchema* schema);

    const Block& block() const { return block_; }
    // The written value, else the schema default, else nullptr.
    const Value* value(std::string_view name) const;
    SourceLocation location(std::string_view name) const;  // attribute's, else the block's

    Result<double> number(std::string_view name) const;  // SI units
    std::optional<double> optionalNumber(std::string_view name) const;
    bool boolean(std::string_view name, bool fallback) const;
    std::string string(std::string_view name, std::string fallback = {}) const;
    std::optional<Color> color(std::string_view name) const;
    std::optional<GeoPosition> geo(std::string_view name) const;
    std::optional<std::string> reference(std::string_view name) const;  // target name
    std::vector<std::string> references(std::string_view name) const;   // list of targets

    // "file:line:col: block 'name': " prefix for messages about this block.
    std::string where(std::string_view attribute = {}) const;

private:
    const Block& block_;
    const KindSchema* schema_;
};

}  // namespace sylva
