#include "sylva/dsl/QuantityText.h"

#include <numbers>

#include "DiagnosticText.h"

namespace sylva::dsl {

std::string formatQuantity(const Quantity& quantity) {
    constexpr double kDegree = std::numbers::pi / 180.0;
    switch (quantity.dimension) {
        case Dimension::None:
            return formatNumber(quantity.value);
        case Dimension::Length:
            return formatNumber(quantity.value) + "m";
        case Dimension::Angle:
            return formatNumber(quantity.value / kDegree) + "deg";
        case Dimension::Time:
            return formatNumber(quantity.value) + "s";
        case Dimension::Ratio:
            return formatNumber(quantity.value * 100.0) + "%";
        case Dimension::Pixels:
            return formatNumber(quantity.value) + "px";
    }
    return formatNumber(quantity.value);
}

}  // namespace sylva::dsl
