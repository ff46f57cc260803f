// SourceFactory: the table from source kind ("noise", "raster" ...) to the function
// that builds a Source from its model Block. To add a kind: implement the Source,
// give it `static Result<std::unique_ptr<Source>> create(const SourceBuildContext&)`,
// add one line to the table in SourceFactory.cpp and its entry to the schema
// (core/schema/BuiltinSchema.cpp).
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <string_view>
#include <vector>

#include "sylva/core/base/Result.h"
#include "sylva/core/scene/BlockReader.h"
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

// nullptr when this build has no implementation of `kind`.
SourceCreator findSourceCreator(std::string_view kind);

}  // namespace sylva
