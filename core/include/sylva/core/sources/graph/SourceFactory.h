// SourceFactory: the table from source kind ("noise", "raster" ...) to the function
// that builds a Source from its model Block. To add a kind: implement the Source,
// give it `static Result<std::unique_ptr<Source>> create(const SourceBuildContext&)`,
// add one line to the table in SourceFactory.cpp and its entry to the schema
// (core/model/BuiltinSchema.cpp).
#pragma once

#include <string_view>

#include "sylva/core/sources/SourceBuildContext.h"

namespace sylva {

// nullptr when this build has no implementation of `kind`.
SourceCreator findSourceCreator(std::string_view kind);

}  // namespace sylva
