#include "DiagnosticText.h"

#include <cstdio>
#include <string_view>

namespace sylva::dsl {

std::string formatNumber(double value) {
    char buffer[40];
    std::snprintf(buffer, sizeof buffer, "%.6g", value);
    return buffer;
}

std::string join(const std::vector<std::string>& items) {
    std::string out;
    for (const std::string& item : items) {
        out += (out.empty() ? "" : ", ") + item;
    }
    return out;
}

std::string withArticle(const std::string& noun) {
    bool vowel = !noun.empty() && std::string_view("aeiou").find(noun[0]) != std::string::npos;
    return (vowel ? "an " : "a ") + noun;
}

std::string referenceTarget(const AttributeSchema& schema) {
    return schema.target.empty() ? std::string("source") : schema.target;
}

std::string expectedName(const AttributeSchema& schema) {
    switch (schema.type) {
        case ValueType::Number:
            return dimensionName(schema.dimension);
        case ValueType::Bool:
            return "bool";
        case ValueType::String:
            return "string";
        case ValueType::Color:
            return "colour";
        case ValueType::Geo:
            return "geo position";
        case ValueType::Word:
            return "one of: " + join(schema.words);
        case ValueType::Reference:
            return schema.port != PortType::None
                       ? std::string(portTypeName(schema.port)) + " source"
                       : referenceTarget(schema);
        case ValueType::List:
            return "list";
        case ValueType::Object:
            return "object";
        case ValueType::DateTime:
            return "date/time";
    }
    return "value";
}

std::string describeBlock(const KindSchema& schema) {
    return schema.keyword == "source" ? schema.kind + " source" : schema.keyword;
}

}  // namespace sylva::dsl
