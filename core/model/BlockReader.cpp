#include "sylva/core/model/BlockReader.h"

namespace sylva {

BlockReader::BlockReader(const Block& block, const KindSchema* schema)
    : block_(block), schema_(schema) {}

const Value* BlockReader::value(std::string_view name) const {
    if (const Attribute* attribute = block_.find(name)) {
        return &attribute->value;
    }
    if (schema_ != nullptr) {
        if (const AttributeSchema* attribute = schema_->find(name)) {
            if (attribute->defaultValue) {
                return &*attribute->defaultValue;
            }
        }
    }
    return nullptr;
}

SourceLocation BlockReader::location(std::string_view name) const {
    if (const Attribute* attribute = block_.find(name)) {
        return attribute->value.location.valid() ? attribute->value.location : attribute->location;
    }
    return block_.location;
}

std::string BlockReader::where(std::string_view attribute) const {
    std::string prefix = location(attribute).toString() + ": ";
    prefix += block_.keyword;
    if (!block_.name.empty()) {
        prefix += " '" + block_.name + "'";
    }
    return prefix + ": ";
}

Result<double> BlockReader::number(std::string_view name) const {
    if (std::optional<double> v = optionalNumber(name)) {
        return *v;
    }
    return Error{where(name) + "missing value for '" + std::string(name) + "'"};
}

std::optional<double> BlockReader::optionalNumber(std::string_view name) const {
    const Value* v = value(name);
    if (v == nullptr) {
        return std::nullopt;
    }
    const Quantity* q = v->get<Quantity>();
    SYLVA_CHECK_MESSAGE(q != nullptr, "BlockReader::number: attribute is not a number");
    return q->value;
}

bool BlockReader::boolean(std::string_view name, bool fallback) const {
    const Value* v = value(name);
    if (v == nullptr) {
        return fallback;
    }
    const bool* b = v->get<bool>();
    SYLVA_CHECK_MESSAGE(b != nullptr, "BlockReader::boolean: attribute is not a bool");
    return *b;
}

std::string BlockReader::string(std::string_view name, std::string fallback) const {
    const Value* v = value(name);
    if (v == nullptr) {
        return fallback;
    }
    const std::string* s = v->get<std::string>();
    SYLVA_CHECK_MESSAGE(s != nullptr, "BlockReader::string: attribute is not a string");
    return *s;
}

std::optional<Color> BlockReader::color(std::string_view name) const {
    const Value* v = value(name);
    if (v == nullptr) {
        return std::nullopt;
    }
    const Color* c = v->get<Color>();
    SYLVA_CHECK_MESSAGE(c != nullptr, "BlockReader::color: attribute is not a colour");
    return *c;
}

std::optional<GeoPosition> BlockReader::geo(std::string_view name) const {
    const Value* v = value(name);
    if (v == nullptr) {
        return std::nullopt;
    }
    const GeoPosition* g = v->get<GeoPosition>();
    SYLVA_CHECK_MESSAGE(g != nullptr, "BlockReader::geo: attribute is not a geo position");
    return *g;
}

std::optional<std::string> BlockReader::reference(std::string_view name) const {
    const Value* v = value(name);
    if (v == nullptr) {
        return std::nullopt;
    }
    const Reference* r = v->get<Reference>();
    SYLVA_CHECK_MESSAGE(r != nullptr, "BlockReader::reference: attribute is not a reference");
    return r->name;
}

std::vector<std::string> BlockReader::references(std::string_view name) const {
    std::vector<std::string> result;
    const Value* v = value(name);
    if (v == nullptr) {
        return result;
    }
    const ValueList* list = v->get<ValueList>();
    SYLVA_CHECK_MESSAGE(list != nullptr, "BlockReader::references: attribute is not a list");
    for (const Value& element : *list) {
        const Reference* r = element.get<Reference>();
        SYLVA_CHECK_MESSAGE(r != nullptr, "BlockReader::references: element is not a reference");
        result.push_back(r->name);
    }
    return result;
}

}  // namespace sylva
