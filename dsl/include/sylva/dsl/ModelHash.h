// Canonical text and content hashes of model values and blocks. Two values with the
// same canonical text are equal for the project language (locations do not count);
// blocks with equal content hashes compute equal data, so scenarios can share them.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "sylva/core/model/ProjectModel.h"
#include "sylva/core/model/Value.h"

namespace sylva::dsl {

// A deterministic text of `value` without locations (numbers with 17 significant digits).
std::string canonicalText(const Value& value);
// 64-bit FNV-1a of `text`.
std::uint64_t fnv1a(const std::string& text);
// Fills Block::contentHash of every block; a source's hash includes the hashes of the
// sources it references, so a change deep in the graph changes every dependant.
// With `changed`, only those sources and the sources depending on them are rehashed; the
// others keep their hash (a scenario copied from the base model and then overridden).
void computeContentHashes(ProjectModel& model, const std::vector<std::string>* changed = nullptr);

}  // namespace sylva::dsl
