// SourceBuildContext: what a source kind's `create` receives to build a Source from its
// model Block (attribute access, its inputs already built, the project folder). Every kind
// implements `static Result<std::unique_ptr<Source>> create(const SourceBuildContext&)`;
// the table from kind names to those functions is SourceFactory (sources/graph).
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <string_view>
#include <vector>

#include "sylva/core/base/Result.h"
#include "sylva/core/model/BlockReader.h"
#include "sylva/core/sources/Source.h"

namespace sylva {

// The input source named by `attribute` of the block being built, already built and
// checked against the attribute's port type. For an absent optional input it returns
// nullptr; for an absent required one an error located at the block.
using InputResolver =
    std::function<Result<const Source*>(std::string_view attribute, bool required)>;

// The sources named by a reference-list attribute (`models = [@oak, @palm]`), built and
// checked against the attribute's port type, in list order; empty when absent. Errors are
// located at the attribute.
using InputListResolver =
    std::function<Result<std::vector<const Source*>>(std::string_view attribute)>;

struct SourceBuildContext {
    const Block& block;
    const BlockReader& reader;   // attribute access with schema defaults
    const InputResolver& input;  // inputs by attribute name
    // Folder of the project file: relative data paths resolve against it.
    std::filesystem::path projectFolder;
    const InputListResolver* inputList = nullptr;  // nullptr: no list inputs available
};

using SourceCreator = Result<std::unique_ptr<Source>> (*)(const SourceBuildContext& context);

}  // namespace sylva
