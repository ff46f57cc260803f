// How the checker's diagnostics name things: numbers, lists, articles, the type an
// attribute expects and the block a schema describes. Shared by the parts of the
// Resolver so the same thing is always worded the same way.
#pragma once

#include <string>
#include <vector>

#include "sylva/core/model/Schema.h"

namespace sylva::dsl {

// A number with up to six significant digits ("2500", "0.333333", "1e+06").
std::string formatNumber(double value);
// "a, b, c".
std::string join(const std::vector<std::string>& items);
// "a length", "an angle".
std::string withArticle(const std::string& noun);
// The block keyword a reference attribute expects ("source" when the schema names none).
std::string referenceTarget(const AttributeSchema& schema);
// What an attribute expects, for "expected X, found Y": "length", "one of: a, b", ...
std::string expectedName(const AttributeSchema& schema);
// "noise source", "camera": a block as its schema describes it.
std::string describeBlock(const KindSchema& schema);

}  // namespace sylva::dsl
