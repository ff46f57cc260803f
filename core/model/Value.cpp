#include "sylva/core/model/Value.h"

namespace sylva {

const char* dimensionName(Dimension dimension) {
    switch (dimension) {
        case Dimension::None:
            return "number";
        case Dimension::Length:
            return "length";
        case Dimension::Angle:
            return "angle";
        case Dimension::Time:
            return "time";
        case Dimension::Ratio:
            return "percentage";
        case Dimension::Pixels:
            return "pixels";
    }
    return "number";
}

std::string Value::typeName() const {
    struct Visitor {
        std::string operator()(std::monostate) const { return "nothing"; }
        std::string operator()(bool) const { return "bool"; }
        std::string operator()(const Quantity& q) const { return dimensionName(q.dimension); }
        std::string operator()(const std::string&) const { return "string"; }
        std::string operator()(const Color&) const { return "colour"; }
        std::string operator()(const GeoPosition&) const { return "geo position"; }
        std::string operator()(const Reference& r) const { return r.kind + " reference"; }
        std::string operator()(const Word&) const { return "word"; }
        std::string operator()(const ValueList&) const { return "list"; }
        std::string operator()(const ValueObject&) const { return "object"; }
    };
    return std::visit(Visitor{}, data);
}

}  // namespace sylva
