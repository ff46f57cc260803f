#include "BuiltinFunctions.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "DiagnosticText.h"
#include "MakeValue.h"
#include "sylva/core/geo/Geodesy.h"
#include "sylva/dsl/EditDistance.h"
#include "sylva/dsl/ModelHash.h"
#include "sylva/dsl/QuantityText.h"

namespace sylva::dsl {

namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

const std::vector<std::string> kFunctions = {
    "geo", "min", "max", "clamp", "interpolate", "step", "match", "distance", "destination"};

// The argument at `index`, located at the call (results stand where the call is written).
Value resultAt(const Expr& call, const std::vector<Value>& arguments, std::size_t index) {
    Value result = arguments[index];
    result.location = call.location;
    return result;
}

}  // namespace

BuiltinFunctions::BuiltinFunctions(ValueChecker& values, std::vector<Diagnostic>& diagnostics)
    : values_(values), diagnostics_(diagnostics) {}

bool BuiltinFunctions::accepts(const Expr& call) {
    if (std::find(kFunctions.begin(), kFunctions.end(), call.text) == kFunctions.end()) {
        Diagnostic& diagnostic =
            addError(diagnostics_, "E0211", "unknown function '" + call.text + "'", call.location,
                     "not a function");
        if (auto match = closestMatch(call.text, kFunctions)) {
            diagnostic.help.push_back("did you mean '" + *match + "'?");
        }
        diagnostic.help.push_back("functions are: " + join(kFunctions));
        return false;
    }
    return hasArity(call);
}

bool BuiltinFunctions::hasArity(const Expr& call) {
    const std::size_t count = call.children.size();
    if (call.text == "geo") {
        if (count >= 2 && count <= 3) {
            return true;
        }
        addError(diagnostics_, "E0407",
                 "geo() takes 2 or 3 arguments, found " + std::to_string(count), call.location,
                 "write geo(latitude, longitude[, height])");
        return false;
    }
    struct Arity {
        const char* function;
        bool fits;
        const char* usage;
    };
    const Arity arities[] = {
        {"min", count >= 1, "one or more values"},
        {"max", count >= 1, "one or more values"},
        {"clamp", count == 3, "value, lowest, highest"},
        {"interpolate", count >= 5 && count % 2 == 1, "x, x1, y1, x2, y2, ..."},
        {"step", count >= 2 && count % 2 == 0, "x, y0, x1, y1, ..."},
        {"match", count >= 4 && count % 2 == 0, "value, key1, result1, ..., default"},
        {"distance", count == 2, "from, to"},
        {"destination", count == 3, "from, bearing, distance"},
    };
    for (const Arity& arity : arities) {
        if (call.text != arity.function) {
            continue;
        }
        if (!arity.fits) {
            const std::string usage = arity.usage;
            addError(diagnostics_, "E0407",
                     call.text + "() takes " + usage + ", found " + std::to_string(count),
                     call.location, "write " + call.text + "(" + usage + ")");
        }
        return arity.fits;
    }
    return true;
}

std::optional<Value> BuiltinFunctions::apply(const Expr& call, std::vector<Value> arguments) {
    if (call.text == "geo") {
        return geo(call, arguments);
    }
    if (call.text == "distance") {
        return distance(call, arguments);
    }
    if (call.text == "destination") {
        return destination(call, arguments);
    }
    if (call.text == "match") {
        return match(call, arguments);
    }
    // The other functions work on quantities; x and the stops share one unit.
    if (!arguments[0].get<Quantity>()) {
        quantityAt(call, arguments, 0, Dimension::None);
        return std::nullopt;
    }
    if (call.text == "min" || call.text == "max" || call.text == "clamp") {
        return extremum(call, arguments);
    }
    if (!stopsAscend(call, arguments)) {
        return std::nullopt;
    }
    return call.text == "step" ? step(call, arguments) : interpolate(call, arguments);
}

std::optional<Value> BuiltinFunctions::geo(const Expr& call, const std::vector<Value>& arguments) {
    std::optional<double> latitude = values_.coerceAngle(arguments[0], "latitude");
    std::optional<double> longitude = values_.coerceAngle(arguments[1], "longitude");
    bool ok = latitude && longitude;
    auto checkRange = [&](std::optional<double> angle, double limit, const char* what,
                          const Value& where) {
        if (angle && (*angle < -limit * kDegree || *angle > limit * kDegree)) {
            addError(diagnostics_, "E0404", std::string(what) + " out of range", where.location,
                     formatQuantity({*angle, Dimension::Angle}) + " is outside [-" +
                         formatNumber(limit) + "deg, " + formatNumber(limit) + "deg]");
            ok = false;
        }
    };
    checkRange(latitude, 90.0, "latitude", arguments[0]);
    checkRange(longitude, 180.0, "longitude", arguments[1]);
    GeoPosition position;
    if (arguments.size() == 3) {
        AttributeSchema heightSchema;
        heightSchema.type = ValueType::Number;
        heightSchema.dimension = Dimension::Length;
        std::optional<Value> height = values_.coerce(arguments[2], heightSchema, "height");
        if (!height) {
            return std::nullopt;
        }
        position.height = height->get<Quantity>()->value;
    }
    if (!ok) {
        return std::nullopt;
    }
    position.latitude = *latitude;
    position.longitude = *longitude;
    return makeValue(position, call.location);
}

// Geodesics on WGS84 (GeographicLib): distance(a, b) in metres; destination(from,
// bearing, distance) keeps from's height.
const GeoPosition* BuiltinFunctions::startOf(const Expr& call,
                                             const std::vector<Value>& arguments) {
    const GeoPosition* from = arguments[0].get<GeoPosition>();
    if (!from) {
        addError(diagnostics_, "E0402", "expected geo position, found " + arguments[0].typeName(),
                 arguments[0].location, call.text + "() starts at a geo position");
    }
    return from;
}

std::optional<Value> BuiltinFunctions::distance(const Expr& call,
                                                const std::vector<Value>& arguments) {
    const GeoPosition* from = startOf(call, arguments);
    if (!from) {
        return std::nullopt;
    }
    const GeoPosition* to = arguments[1].get<GeoPosition>();
    if (!to) {
        addError(diagnostics_, "E0402", "expected geo position, found " + arguments[1].typeName(),
                 arguments[1].location, "distance() measures between two geo positions");
        return std::nullopt;
    }
    return makeValue(
        Quantity{Geodesy::distance(from->latitude, from->longitude, to->latitude, to->longitude),
                 Dimension::Length},
        call.location);
}

std::optional<Value> BuiltinFunctions::destination(const Expr& call,
                                                   const std::vector<Value>& arguments) {
    const GeoPosition* from = startOf(call, arguments);
    if (!from) {
        return std::nullopt;
    }
    const Quantity* bearing = arguments[1].get<Quantity>();
    const Quantity* length = arguments[2].get<Quantity>();
    if (!bearing || bearing->dimension != Dimension::Angle) {
        addError(diagnostics_, "E0403", "expected angle, found " + arguments[1].typeName(),
                 arguments[1].location, "the bearing of destination() must be an angle");
        return std::nullopt;
    }
    if (!length || length->dimension != Dimension::Length) {
        addError(diagnostics_, "E0403", "expected length, found " + arguments[2].typeName(),
                 arguments[2].location, "the distance of destination() must be a length");
        return std::nullopt;
    }
    GeoPosition reached = *from;
    Geodesy::destination(from->latitude, from->longitude, bearing->value, length->value,
                         reached.latitude, reached.longitude);
    return makeValue(reached, call.location);
}

std::optional<Value> BuiltinFunctions::match(const Expr& call,
                                             const std::vector<Value>& arguments) {
    std::string key = canonicalText(arguments[0]);
    for (std::size_t i = 1; i + 1 < arguments.size(); i += 2) {
        if (canonicalText(arguments[i]) == key) {
            return resultAt(call, arguments, i + 1);
        }
    }
    return resultAt(call, arguments, arguments.size() - 1);
}

const Quantity* BuiltinFunctions::quantityAt(const Expr& call, const std::vector<Value>& arguments,
                                             std::size_t i, Dimension dimension) {
    const Quantity* quantity = arguments[i].get<Quantity>();
    if (!quantity) {
        addError(diagnostics_, "E0402", "expected a number, found " + arguments[i].typeName(),
                 arguments[i].location, call.text + "() works on numbers and quantities");
        return nullptr;
    }
    if (quantity->dimension != dimension) {
        addError(diagnostics_, "E0403",
                 std::string("expected ") + dimensionName(dimension) + ", found " +
                     dimensionName(quantity->dimension),
                 arguments[i].location, "the arguments of " + call.text + "() must share one unit");
        return nullptr;
    }
    return quantity;
}

std::optional<Value> BuiltinFunctions::extremum(const Expr& call,
                                                const std::vector<Value>& arguments) {
    const Quantity* first = arguments[0].get<Quantity>();
    Quantity result = *first;
    for (std::size_t i = 1; i < arguments.size(); ++i) {
        const Quantity* other = quantityAt(call, arguments, i, first->dimension);
        if (!other) {
            return std::nullopt;
        }
        if (call.text == "min" || (call.text == "clamp" && i == 2)) {
            result.value = std::min(result.value, other->value);
        } else {
            result.value = std::max(result.value, other->value);
        }
    }
    return makeValue(result, call.location);
}

bool BuiltinFunctions::stopsAscend(const Expr& call, const std::vector<Value>& arguments) {
    // step(x, y0, x1, y1, ...) has its stops at even positions from 2,
    // interpolate(x, x1, y1, x2, y2, ...) at odd positions from 1.
    const Dimension unit = arguments[0].get<Quantity>()->dimension;
    const std::size_t firstStop = call.text == "step" ? 2 : 1;
    double previous = -HUGE_VAL;
    for (std::size_t i = firstStop; i < arguments.size(); i += 2) {
        const Quantity* stop = quantityAt(call, arguments, i, unit);
        if (!stop) {
            return false;
        }
        if (stop->value < previous) {
            addError(diagnostics_, "E0404", "stops of " + call.text + "() must ascend",
                     arguments[i].location, "smaller than the stop before it");
            return false;
        }
        previous = stop->value;
    }
    return true;
}

std::optional<Value> BuiltinFunctions::step(const Expr& call, const std::vector<Value>& arguments) {
    const double x = arguments[0].get<Quantity>()->value;
    std::size_t chosen = 1;
    for (std::size_t i = 2; i < arguments.size(); i += 2) {
        if (x >= arguments[i].get<Quantity>()->value) {
            chosen = i + 1;
        }
    }
    return resultAt(call, arguments, chosen);
}

std::optional<Value> BuiltinFunctions::interpolate(const Expr& call,
                                                   const std::vector<Value>& arguments) {
    const double x = arguments[0].get<Quantity>()->value;
    const Quantity* output = arguments[2].get<Quantity>();
    const Color* colour = arguments[2].get<Color>();
    for (std::size_t i = 2; i < arguments.size(); i += 2) {
        if (output && !quantityAt(call, arguments, i, output->dimension)) {
            return std::nullopt;
        }
        if (!output && (!colour || !arguments[i].get<Color>())) {
            addError(diagnostics_, "E0402",
                     "expected a quantity or colour, found " + arguments[i].typeName(),
                     arguments[i].location, "interpolate() blends quantities or colours");
            return std::nullopt;
        }
    }
    std::size_t upper = 1;
    while (upper < arguments.size() && arguments[upper].get<Quantity>()->value < x) {
        upper += 2;
    }
    if (upper == 1 || upper >= arguments.size()) {
        // Outside the stops: hold the nearest end.
        return resultAt(call, arguments, upper == 1 ? 2 : arguments.size() - 1);
    }
    const double x0 = arguments[upper - 2].get<Quantity>()->value;
    const double x1 = arguments[upper].get<Quantity>()->value;
    const double t = x1 > x0 ? (x - x0) / (x1 - x0) : 1.0;
    const Value& a = arguments[upper - 1];
    const Value& b = arguments[upper + 1];
    if (output) {
        Quantity result{a.get<Quantity>()->value * (1 - t) + b.get<Quantity>()->value * t,
                        output->dimension};
        return makeValue(result, call.location);
    }
    const Color& ca = *a.get<Color>();
    const Color& cb = *b.get<Color>();
    auto mix = [&](float u, float v) { return static_cast<float>(u * (1 - t) + v * t); };
    return makeValue(Color{mix(ca.r, cb.r), mix(ca.g, cb.g), mix(ca.b, cb.b), mix(ca.a, cb.a)},
                     call.location);
}

}  // namespace sylva::dsl
