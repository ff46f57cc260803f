#include "sylva/core/model/Schema.h"

#include "sylva/core/base/Check.h"

#include <utility>

namespace sylva {

const char* portTypeName(PortType type) {
    switch (type) {
        case PortType::None:
            return "none";
        case PortType::Elevation:
            return "elevation";
        case PortType::Image:
            return "image";
        case PortType::Normals:
            return "normals";
        case PortType::Mask:
            return "mask";
        case PortType::Features:
            return "features";
        case PortType::Instances:
            return "instances";
        case PortType::PlantModel:
            return "plant_model";
        case PortType::Meshes:
            return "meshes";
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

void SchemaRegistry::add(KindSchema kind) {
    kinds_.push_back(std::move(kind));
}

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

void SchemaRegistry::setOutputFrom(std::string_view kind, std::string attribute) {
    SYLVA_CHECK(find("source", kind) != nullptr);
    outputFrom_.emplace_back(std::string(kind), std::move(attribute));
}

std::string_view SchemaRegistry::outputFrom(std::string_view kind) const {
    for (const auto& [name, attribute] : outputFrom_) {
        if (name == kind) {
            return attribute;
        }
    }
    return {};
}

}  // namespace sylva
