// Checks the season and growth attributes of `plants` blocks when a project loads
// (E0415), with the rules the graph build applies (PlantSeasons::read): a malformed
// "MM-DD" day or days out of order in `phenology`, a species the block does not have, a
// growth curve whose ages do not increase, `growth` without `planted`. Types, units and
// negative values of `growth` points are the schema's (E0402, E0403, E0404).
#pragma once

#include <vector>

#include "sylva/core/model/ProjectModel.h"
#include "sylva/dsl/Diagnostic.h"

namespace sylva::dsl {

// Reports the first problem of a `plants` source block (other blocks: nothing).
void checkPlantSeasons(const Block& block, std::vector<Diagnostic>& diagnostics);

}  // namespace sylva::dsl
