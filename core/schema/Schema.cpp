#include "sylva/core/schema/Schema.h"

#include <utility>

namespace sylva {

const char* portTypeName(PortType type) {
    switch (type) {
        case PortType::None: return "none";
        case PortType::Elevation: return "elevation";
        case PortType::Image: return "image";
        case PortType::Normals: return "normals";
        case PortType::Mask: return "mask";
        case PortType::Features: return "features";
        case PortType::Instances: return "instances";
    }
    return "none";
}

const AttributeSchema* KindSchema::find(std::string_view name) const {
    for (const AttributeSchema& attribute : attributes) {
        if (attribute.name == name) {
            return &attribute;
        }
    }
    return nullptr;
}

void SchemaRegistry::add(KindSchema kind) { kinds_.push_back(std::move(kind)); }

const KindSchema* SchemaRegistry::find(std::string_view keyword, std::string_view kind) const {
    for (const KindSchema& candidate : kinds_) {
        if (candidate.keyword == keyword && candidate.kind == kind) {
            return &candidate;
        }
    }
    return nullptr;
}

std::vector<std::string> SchemaRegistry::sourceKinds() const {
    std::vector<std::string> result;
    for (const KindSchema& candidate : kinds_) {
        if (candidate.keyword == "source") {
            result.push_back(candidate.kind);
        }
    }
    return result;
}

}  // namespace sylva
