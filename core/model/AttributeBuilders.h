// Small builders for the schema tables of the project language (BuiltinSchema.cpp,
// LanguageSchema.cpp, AnalysisSchema.cpp): one place for the attribute every table
// starts from. Private to core/model.
#pragma once

#include <string>
#include <utility>

#include "sylva/core/model/Schema.h"

namespace sylva::schema {

// An attribute with its name, value type and reference text; everything else defaulted
// (optional, no default value, no limits).
inline AttributeSchema attribute(std::string name, ValueType type, std::string doc) {
    AttributeSchema a;
    a.name = std::move(name);
    a.type = type;
    a.doc = std::move(doc);
    return a;
}

}  // namespace sylva::schema
