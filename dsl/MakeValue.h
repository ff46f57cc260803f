// A model Value holding `data`, located where it was written.
#pragma once

#include <utility>

#include "sylva/core/model/Value.h"

namespace sylva::dsl {

template <typename T>
Value makeValue(T data, const SourceLocation& location) {
    Value value;
    value.data = std::move(data);
    value.location = location;
    return value;
}

}  // namespace sylva::dsl
