#include "ValueChecker.h"

#include <algorithm>
#include <numbers>
#include <string_view>
#include <utility>

#include "DiagnosticText.h"
#include "sylva/core/geo/ProjectedCoordinates.h"
#include "sylva/dsl/EditDistance.h"
#include "sylva/dsl/QuantityText.h"

namespace sylva::dsl {

namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

// The unit a bare number is read in, per dimension, and its scale to SI.
struct AssumedUnit {
    const char* name;
    double scale;
};
AssumedUnit assumedUnit(Dimension dimension) {
    switch (dimension) {
        case Dimension::Length:
            return {"metres", 1.0};
        case Dimension::Angle:
            return {"degrees", kDegree};
        case Dimension::Time:
            return {"seconds", 1.0};
        case Dimension::Ratio:
            return {"a fraction", 1.0};
        case Dimension::Pixels:
            return {"pixels", 1.0};
        case Dimension::None:
            break;
    }
    return {"", 1.0};
}

// The forms the lexer produces: 2024-06-21, 2024-06-21T14:30:00[+02:00], 14:30:00.
bool isCanonicalDateTime(const std::string& text) {
    auto shape = [&](const char* pattern) {
        std::string_view p(pattern);
        if (text.size() != p.size()) {
            return false;
        }
        for (std::size_t i = 0; i < p.size(); ++i) {
            bool digit = text[i] >= '0' && text[i] <= '9';
            if (p[i] == 'd' ? !digit
                            : (p[i] == 's' ? text[i] != '+' && text[i] != '-' : text[i] != p[i])) {
                return false;
            }
        }
        return true;
    };
    return shape("dddd-dd-dd") || shape("dddd-dd-ddTdd:dd:dd") ||
           shape("dddd-dd-ddTdd:dd:ddsdd:dd") || shape("dd:dd:dd");
}

}  // namespace

ValueChecker::ValueChecker(const NameScope& names, std::vector<Diagnostic>& diagnostics)
    : names_(names), diagnostics_(diagnostics) {}

std::optional<Value> ValueChecker::coerce(Value value, const AttributeSchema& schema,
                                          const std::string& what) {
    switch (schema.type) {
        case ValueType::Number:
            return coerceNumber(std::move(value), schema, what);
        case ValueType::Bool:
            return value.get<bool>() ? std::optional<Value>(std::move(value))
                                     : wrongType(value, schema, what);
        case ValueType::String:
            return value.get<std::string>() ? std::optional<Value>(std::move(value))
                                            : wrongType(value, schema, what);
        case ValueType::Color:
            return value.get<Color>() ? std::optional<Value>(std::move(value))
                                      : wrongType(value, schema, what);
        case ValueType::Geo:
            return coerceGeo(std::move(value), schema, what);
        case ValueType::DateTime: {
            const std::string* text = value.get<std::string>();
            if (!text || !isCanonicalDateTime(*text)) {
                return wrongType(value, schema, what);
            }
            return value;
        }
        case ValueType::Object:
            return coerceObject(std::move(value), schema, what);
        case ValueType::Word:
            return coerceWord(std::move(value), schema, what);
        case ValueType::Reference:
            return coerceReference(std::move(value), schema, what);
        case ValueType::List:
            return coerceList(std::move(value), schema, what);
    }
    return std::nullopt;
}

std::optional<double> ValueChecker::coerceAngle(const Value& value, const std::string& what) {
    const Quantity* quantity = value.get<Quantity>();
    if (!quantity) {
        addError(diagnostics_, "E0402", "expected angle, found " + value.typeName(), value.location,
                 what + " must be an angle");
        return std::nullopt;
    }
    if (quantity->dimension == Dimension::None) {
        Quantity read{quantity->value * kDegree, Dimension::Angle};
        addWarning(diagnostics_, "W0101",
                   "bare number where an angle is expected; assuming degrees", value.location,
                   "read as " + formatQuantity(read));
        return read.value;
    }
    if (quantity->dimension != Dimension::Angle) {
        addError(diagnostics_, "E0403",
                 std::string("expected angle, found ") + dimensionName(quantity->dimension),
                 value.location, what + " must be an angle");
        return std::nullopt;
    }
    return quantity->value;
}

std::optional<Value> ValueChecker::wrongType(const Value& value, const AttributeSchema& schema,
                                             const std::string& what) {
    addError(diagnostics_, "E0402",
             "expected " + expectedName(schema) + ", found " + value.typeName(), value.location,
             what + " must be " + withArticle(expectedName(schema)));
    return std::nullopt;
}

std::optional<Value> ValueChecker::coerceNumber(Value value, const AttributeSchema& schema,
                                                const std::string& what) {
    Quantity* quantity = std::get_if<Quantity>(&value.data);
    if (!quantity) {
        return wrongType(value, schema, what);
    }
    if (quantity->dimension != schema.dimension) {
        if (quantity->dimension != Dimension::None) {
            addError(diagnostics_, "E0403",
                     std::string("expected ") + dimensionName(schema.dimension) + ", found " +
                         dimensionName(quantity->dimension),
                     value.location,
                     what + " must be " + withArticle(dimensionName(schema.dimension)));
            return std::nullopt;
        }
        AssumedUnit unit = assumedUnit(schema.dimension);
        quantity->value *= unit.scale;
        quantity->dimension = schema.dimension;
        addWarning(diagnostics_, "W0101",
                   std::string("bare number where ") +
                       withArticle(schema.dimension == Dimension::Pixels
                                       ? "pixel count"
                                       : dimensionName(schema.dimension)) +
                       " is expected; assuming " + unit.name,
                   value.location, "read as " + formatQuantity(*quantity));
    }
    if (schema.minimum && quantity->value < *schema.minimum) {
        addError(diagnostics_, "E0404", "value out of range for " + what, value.location,
                 formatQuantity(*quantity) + " is below the minimum " +
                     formatQuantity({*schema.minimum, schema.dimension}));
        return std::nullopt;
    }
    if (schema.maximum && quantity->value > *schema.maximum) {
        addError(diagnostics_, "E0404", "value out of range for " + what, value.location,
                 formatQuantity(*quantity) + " is above the maximum " +
                     formatQuantity({*schema.maximum, schema.dimension}));
        return std::nullopt;
    }
    return value;
}

std::optional<Value> ValueChecker::coerceGeo(Value value, const AttributeSchema& schema,
                                             const std::string& what) {
    if (value.get<GeoPosition>()) {
        return value;
    }
    // [x, y] or [x, y, height] lengths: a position in the project's CRS.
    const ValueList* list = value.get<ValueList>();
    const auto isLength = [](const Value& element) {
        const Quantity* q = element.get<Quantity>();
        return q != nullptr && q->dimension == Dimension::Length;
    };
    if (list == nullptr || (list->size() != 2 && list->size() != 3) ||
        !std::all_of(list->begin(), list->end(), isLength)) {
        return wrongType(value, schema, what);
    }
    if (!projectCrs_ && projectCrsInvalid_) {
        return std::nullopt;  // the bad CRS itself is the error
    }
    if (!projectCrs_) {
        Diagnostic& diagnostic = addError(diagnostics_, "E0413",
                                          "position in projected coordinates without a project CRS",
                                          value.location, what + " is written as [x, y] lengths");
        diagnostic.help.push_back(
            "declare the CRS, e.g. project { crs = \"EPSG:31985\" }, or write geo(lat, "
            "lon)");
        return std::nullopt;
    }
    const std::string& crs = *projectCrs_->get<std::string>();
    Result<GeodeticPoint> point = ProjectedCoordinates::toGeodetic(
        crs, (*list)[0].get<Quantity>()->value, (*list)[1].get<Quantity>()->value);
    if (!point) {
        Diagnostic& diagnostic = addError(diagnostics_, "E0414", point.error().message,
                                          value.location, "outside what '" + crs + "' can convert");
        diagnostic.notes.push_back({"the project CRS is declared here", projectCrs_->location});
        return std::nullopt;
    }
    GeoPosition position{point->latitude, point->longitude, std::nullopt};
    if (list->size() == 3) {
        position.height = (*list)[2].get<Quantity>()->value;
    }
    Value converted;
    converted.data = position;
    converted.location = value.location;
    return converted;
}

std::optional<Value> ValueChecker::coerceObject(Value value, const AttributeSchema& schema,
                                                const std::string& what) {
    ValueObject* object = std::get_if<ValueObject>(&value.data);
    if (!object) {
        return wrongType(value, schema, what);
    }
    if (schema.fields.empty()) {
        return value;
    }
    bool ok = true;
    std::vector<std::string> valid;
    for (const AttributeSchema& field : schema.fields) {
        valid.push_back(field.name);
    }
    for (auto& [key, item] : *object) {
        const AttributeSchema* field = nullptr;
        for (const AttributeSchema& candidate : schema.fields) {
            if (candidate.name == key) {
                field = &candidate;
            }
        }
        if (!field) {
            Diagnostic& diagnostic = addError(diagnostics_, "E0208", "unknown key '" + key + "'",
                                              item.location, "not a key of " + what);
            if (auto match = closestMatch(key, valid)) {
                diagnostic.help.push_back("did you mean '" + *match + "'?");
            }
            diagnostic.help.push_back("valid keys: " + join(valid));
            ok = false;
            continue;
        }
        std::optional<Value> checked = coerce(item, *field, "'" + key + "'");
        if (checked) {
            item = std::move(*checked);
        } else {
            ok = false;
        }
    }
    for (const AttributeSchema& field : schema.fields) {
        bool present = std::any_of(object->begin(), object->end(),
                                   [&](const auto& entry) { return entry.first == field.name; });
        if (field.required && !present) {
            addError(diagnostics_, "E0405", "missing required key '" + field.name + "'",
                     value.location, what + " needs '" + field.name + "'")
                .help.push_back(field.name + ": " + field.doc);
            ok = false;
        }
    }
    return ok ? std::optional<Value>(std::move(value)) : std::nullopt;
}

std::optional<Value> ValueChecker::coerceWord(Value value, const AttributeSchema& schema,
                                              const std::string& what) {
    const Word* word = value.get<Word>();
    if (!word) {
        return wrongType(value, schema, what);
    }
    if (!schema.words.empty() &&
        std::find(schema.words.begin(), schema.words.end(), word->text) == schema.words.end()) {
        Diagnostic& diagnostic =
            addError(diagnostics_, "E0410", "unknown word '" + word->text + "' for " + what,
                     value.location, "expected one of: " + join(schema.words));
        if (auto match = closestMatch(word->text, schema.words)) {
            diagnostic.help.push_back("did you mean '" + *match + "'?");
        }
        return std::nullopt;
    }
    return value;
}

std::optional<Value> ValueChecker::coerceReference(Value value, const AttributeSchema& schema,
                                                   const std::string& what) {
    const Reference* reference = value.get<Reference>();
    std::string target = referenceTarget(schema);
    if (!reference) {
        addError(diagnostics_, "E0402",
                 "expected " + expectedName(schema) + " reference, found " + value.typeName(),
                 value.location, what + " must be a reference like '@name'");
        return std::nullopt;
    }
    if (reference->kind != target) {
        addError(diagnostics_, "E0406", "expected " + target + ", found " + reference->kind,
                 value.location, "'" + reference->name + "' is " + withArticle(reference->kind));
        return std::nullopt;
    }
    if (target != "source" || schema.port == PortType::None) {
        return value;
    }
    // Sources whose output follows their attributes are checked by the GraphChecker once
    // the whole graph is known.
    const Declaration* declaration = names_.find(reference->name);
    if (declaration && declaration->schema && declaration->schema->output != PortType::None &&
        declaration->schema->output != schema.port) {
        addError(diagnostics_, "E0406",
                 std::string("expected ") + portTypeName(schema.port) + ", found " +
                     portTypeName(declaration->schema->output),
                 value.location,
                 "'" + reference->name + "' is " + withArticle(declaration->kind) +
                     " source, which outputs " + portTypeName(declaration->schema->output));
        return std::nullopt;
    }
    return value;
}

std::optional<Value> ValueChecker::coerceList(Value value, const AttributeSchema& schema,
                                              const std::string& what) {
    ValueList* list = std::get_if<ValueList>(&value.data);
    if (!list) {
        return wrongType(value, schema, what);
    }
    AttributeSchema element;
    element.type = schema.element;
    element.dimension = schema.dimension;
    element.port = schema.port;
    element.target = schema.target;
    element.minimum = schema.minimum;
    element.maximum = schema.maximum;
    element.fields = schema.fields;
    bool ok = true;
    for (Value& item : *list) {
        // A list of records (a hypsometric ramp) cannot be described by `element`;
        // its consumer checks the records.
        if (schema.element == ValueType::Number && schema.dimension == Dimension::None &&
            item.get<ValueObject>()) {
            continue;
        }
        std::optional<Value> checked = coerce(std::move(item), element, what);
        if (checked) {
            item = std::move(*checked);
        } else {
            ok = false;
        }
    }
    return ok ? std::optional<Value>(std::move(value)) : std::nullopt;
}

}  // namespace sylva::dsl
