// Quantities as users write them, for messages, `sylva doc` and `sylva check
// --print-params`.
#pragma once

#include <string>

#include "sylva/core/model/Value.h"

namespace sylva::dsl {

// "2500m", "30deg", "80%", "20s", "320px", "7": a quantity in the units users write
// (six significant digits).
std::string formatQuantity(const Quantity& quantity);

}  // namespace sylva::dsl
