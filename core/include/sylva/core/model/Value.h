// Values of the project model: what attributes of blocks hold after the DSL has
// parsed, resolved and evaluated them. Plain data, no behaviour beyond access.
// Quantities are normalised to SI: metres, radians, seconds; percentages become
// fractions (80% -> 0.8); pixels stay pixels.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "sylva/core/base/SourceLocation.h"

namespace sylva {

enum class Dimension {
    None,    // a plain number
    Length,  // metres
    Angle,   // radians
    Time,    // seconds
    Ratio,   // a fraction written as a percentage (80% -> 0.8)
    Pixels,  // screen pixels
};

const char* dimensionName(Dimension dimension);  // "number", "length", "angle", ...

struct Quantity {
    double value = 0.0;  // in SI units of `dimension`
    Dimension dimension = Dimension::None;
};

// A colour as written (#RRGGBB[AA]): sRGB-encoded components in [0, 1].
struct Color {
    float r = 0, g = 0, b = 0, a = 1;
};

// A geographic position on WGS84: geodetic latitude and longitude in radians,
// height above the ellipsoid in metres (present only if written).
struct GeoPosition {
    double latitude = 0.0;
    double longitude = 0.0;
    std::optional<double> height;
};

// A resolved reference to a named block (a source, camera, scenario ...).
struct Reference {
    std::string kind;  // block keyword of the target: "source", "camera", "scenario" ...
    std::string name;  // the target's name
};

// An enum word written bare in the project file (`multiply`, `catmull_rom`).
struct Word {
    std::string text;
};

struct Value;
using ValueList = std::vector<Value>;
using ValueObject = std::vector<std::pair<std::string, Value>>;

struct Value {
    std::variant<std::monostate, bool, Quantity, std::string, Color, GeoPosition, Reference, Word,
                 ValueList, ValueObject>
        data;
    SourceLocation location;  // where the value was written

    template <typename T>
    const T* get() const {
        return std::get_if<T>(&data);
    }
    bool empty() const { return std::holds_alternative<std::monostate>(data); }
    // A short name of the held type for messages: "number", "length", "string", "list" ...
    std::string typeName() const;
};

}  // namespace sylva
