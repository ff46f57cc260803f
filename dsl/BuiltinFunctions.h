// The functions of the project language: geo(), min(), max(), clamp(), interpolate(),
// step(), match(), distance() and destination(). A call is checked in two steps: its
// name and number of arguments before anything is evaluated (E0211, E0407), then the
// evaluated arguments (E0402 type, E0403 unit, E0404 range or order of stops).
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "ValueChecker.h"
#include "sylva/core/model/Value.h"
#include "sylva/dsl/Ast.h"
#include "sylva/dsl/Diagnostic.h"

namespace sylva::dsl {

class BuiltinFunctions {
public:
    // `values` reads the angles and height of geo() as attributes do.
    BuiltinFunctions(ValueChecker& values, std::vector<Diagnostic>& diagnostics);

    // Whether `call` names a function and has a number of arguments it takes.
    bool accepts(const Expr& call);
    // The value of an accepted `call` from its evaluated arguments; nullopt after an error.
    std::optional<Value> apply(const Expr& call, std::vector<Value> arguments);

private:
    bool hasArity(const Expr& call);
    std::optional<Value> geo(const Expr& call, const std::vector<Value>& arguments);
    // The geo position a geodesic starts at (E0402 when it is none).
    const GeoPosition* startOf(const Expr& call, const std::vector<Value>& arguments);
    std::optional<Value> distance(const Expr& call, const std::vector<Value>& arguments);
    std::optional<Value> destination(const Expr& call, const std::vector<Value>& arguments);
    std::optional<Value> match(const Expr& call, const std::vector<Value>& arguments);
    // Argument i as a quantity of `dimension`, or nullptr after reporting why not.
    const Quantity* quantityAt(const Expr& call, const std::vector<Value>& arguments, std::size_t i,
                               Dimension dimension);
    std::optional<Value> extremum(const Expr& call, const std::vector<Value>& arguments);
    // The stops of step()/interpolate() are quantities of x's unit in ascending order.
    bool stopsAscend(const Expr& call, const std::vector<Value>& arguments);
    std::optional<Value> step(const Expr& call, const std::vector<Value>& arguments);
    std::optional<Value> interpolate(const Expr& call, const std::vector<Value>& arguments);

    ValueChecker& values_;
    std::vector<Diagnostic>& diagnostics_;
};

}  // namespace sylva::dsl
