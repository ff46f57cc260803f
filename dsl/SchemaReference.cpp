#include "sylva/dsl/SchemaReference.h"

#include <cstdio>

#include "sylva/dsl/ModelHash.h"
#include "sylva/dsl/QuantityText.h"

namespace sylva::dsl {

namespace {

std::string typeText(const AttributeSchema& a) {
    switch (a.type) {
        case ValueType::Number:
            return a.dimension == Dimension::None ? "number" : dimensionName(a.dimension);
        case ValueType::Bool:
            return "bool";
        case ValueType::String:
            return "string";
        case ValueType::Color:
            return "colour";
        case ValueType::Geo:
            return "geo";
        case ValueType::Word: {
            std::string out = "one of";
            for (std::size_t i = 0; i < a.words.size(); ++i) {
                out += (i == 0 ? " " : " | ") + a.words[i];
            }
            return out;
        }
        case ValueType::Reference:
            if (a.port != PortType::None) {
                return std::string("@") + portTypeName(a.port) + " source";
            }
            return "@" + (a.target.empty() ? std::string("source") : a.target);
        case ValueType::List: {
            AttributeSchema element = a;
            element.type = a.element;
            return "list of " +
                   (a.element == ValueType::List ? std::string("lists") : typeText(element));
        }
        case ValueType::Object:
            return "object";
        case ValueType::DateTime:
            return "date/time";
    }
    return "value";
}

std::string valueText(const Value& value) {
    if (const Quantity* q = value.get<Quantity>()) {
        return formatQuantity(*q);
    }
    if (const std::string* s = value.get<std::string>()) {
        return "\"" + *s + "\"";
    }
    if (const bool* b = value.get<bool>()) {
        return *b ? "true" : "false";
    }
    if (const Word* w = value.get<Word>()) {
        return w->text;
    }
    if (const Color* c = value.get<Color>()) {
        char buffer[16];
        auto byte = [](float v) { return static_cast<unsigned>(v * 255.0f + 0.5f); };
        std::snprintf(buffer, sizeof buffer, "#%02x%02x%02x", byte(c->r), byte(c->g), byte(c->b));
        return buffer;
    }
    if (const GeoPosition* g = value.get<GeoPosition>()) {
        std::string out = "geo(" + formatQuantity({g->latitude, Dimension::Angle}) + ", " +
                          formatQuantity({g->longitude, Dimension::Angle});
        if (g->height) {
            out += ", " + formatQuantity({*g->height, Dimension::Length});
        }
        return out + ")";
    }
    if (const ValueList* list = value.get<ValueList>()) {
        std::string out = "[";
        for (std::size_t i = 0; i < list->size(); ++i) {
            out += (i ? ", " : "") + valueText((*list)[i]);
        }
        return out + "]";
    }
    return canonicalText(value);
}

std::string rangeText(const AttributeSchema& a) {
    if (!a.minimum && !a.maximum) {
        return "";
    }
    Dimension d =
        a.type == ValueType::Number || a.type == ValueType::List ? a.dimension : Dimension::None;
    std::string low = a.minimum ? formatQuantity({*a.minimum, d}) : "";
    std::string high = a.maximum ? formatQuantity({*a.maximum, d}) : "";
    return low + " .. " + high;
}

std::string defaultText(const AttributeSchema& a) {
    if (a.required) {
        return "required";
    }
    return a.defaultValue ? valueText(*a.defaultValue) : "optional";
}

std::string title(const KindSchema& kind) {
    return kind.keyword == "source" ? "source NAME : " + kind.kind : kind.keyword;
}

std::string escapeCell(std::string text) {
    std::string out;
    for (char c : text) {
        if (c == '|') {
            out += "\\|";
        } else {
            out += c;
        }
    }
    return out;
}

void table(std::string& out, const std::vector<AttributeSchema>& attributes) {
    out += "| attribute | type | default | range | description |\n";
    out += "|---|---|---|---|---|\n";
    for (const AttributeSchema& a : attributes) {
        out += "| `" + a.name + "` | " + escapeCell(typeText(a)) + " | " +
               escapeCell(defaultText(a)) + " | " + escapeCell(rangeText(a)) + " | " +
               escapeCell(a.doc) + " |\n";
        for (const AttributeSchema& field : a.fields) {
            out += "| `" + a.name + "[]." + field.name + "` | " + escapeCell(typeText(field)) +
                   " | " + escapeCell(defaultText(field)) + " | " + escapeCell(rangeText(field)) +
                   " | " + escapeCell(field.doc) + " |\n";
        }
    }
}

// "elevation", or for kinds whose output follows an attribute, which one decides it.
std::string outputText(const SchemaRegistry& registry, const KindSchema& kind) {
    if (kind.output != PortType::None) {
        return portTypeName(kind.output);
    }
    const std::string_view decidedBy = registry.outputFrom(kind.kind);
    if (decidedBy.empty()) {
        return "decided when the graph is built";
    }
    const AttributeSchema* attribute = kind.find(decidedBy);
    if (attribute && attribute->type == ValueType::Reference) {
        return "the output type of `" + std::string(decidedBy) + "`";
    }
    return "as `" + std::string(decidedBy) + "` says";
}

}  // namespace

std::string SchemaReference::markdown(const SchemaRegistry& registry) {
    std::string out;
    out += "## Reference: blocks and source kinds\n\n";
    out += "Generated from the schema registry by `sylva doc --markdown`; do not edit by hand.\n";
    for (const KindSchema& kind : registry.all()) {
        out += "\n### `" + title(kind) + "`\n\n";
        out += kind.doc + "\n";
        if (kind.keyword == "source") {
            out += "\nOutput: " + outputText(registry, kind) + ".\n";
        }
        if (!kind.attributes.empty()) {
            out += "\n";
            table(out, kind.attributes);
        }
    }
    return out;
}

std::vector<std::string> SchemaReference::names(const SchemaRegistry& registry) {
    std::vector<std::string> names;
    for (const KindSchema& kind : registry.all()) {
        names.push_back(kind.keyword == "source" ? kind.kind : kind.keyword);
    }
    return names;
}

std::string SchemaReference::text(const SchemaRegistry& registry, const std::string& name) {
    for (const KindSchema& kind : registry.all()) {
        if ((kind.keyword == "source" ? kind.kind : kind.keyword) != name) {
            continue;
        }
        std::string out = title(kind) + "\n\n  " + kind.doc + "\n";
        if (kind.keyword == "source") {
            out += "  output: " + outputText(registry, kind) + "\n";
        }
        out += "\n";
        std::vector<const AttributeSchema*> all;
        for (const AttributeSchema& a : kind.attributes) {
            all.push_back(&a);
        }
        for (const AttributeSchema* a : all) {
            out += "  " + a->name + " : " + typeText(*a) + " = " + defaultText(*a);
            std::string range = rangeText(*a);
            if (!range.empty()) {
                out += "  [" + range + "]";
            }
            out += "\n      " + a->doc + "\n";
            for (const AttributeSchema& field : a->fields) {
                out += "      ." + field.name + " : " + typeText(field) + " = " +
                       defaultText(field) + "\n          " + field.doc + "\n";
            }
        }
        return out;
    }
    return "";
}

std::string SchemaReference::replaceGenerated(const std::string& document,
                                              const SchemaRegistry& registry) {
    std::size_t begin = document.find(kBeginMarker);
    std::size_t end = document.find(kEndMarker);
    if (begin == std::string::npos || end == std::string::npos || end < begin) {
        return "";
    }
    begin += std::string(kBeginMarker).size();
    return document.substr(0, begin) + "\n" + markdown(registry) + document.substr(end);
}

}  // namespace sylva::dsl
