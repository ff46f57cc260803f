// Checks an evaluated Value against the schema of the attribute (or param type, object
// key, list element) it is written for, and converts it to the form the model holds:
// a bare number where a quantity is expected is read in the assumed unit (W0101), a
// position written as [x, y] lengths is converted from the project CRS to WGS84.
// Problems are E0402 (type), E0403 (unit), E0404 (range), E0405 (missing key), E0406
// (reference target or port type), E0208 (unknown key), E0410 (unknown word),
// E0413/E0414 (projected positions).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "NameScope.h"
#include "sylva/core/model/Schema.h"
#include "sylva/core/model/Value.h"
#include "sylva/dsl/Diagnostic.h"

namespace sylva::dsl {

class ValueChecker {
public:
    // `names` gives the schema of referenced sources (for their fixed output port).
    ValueChecker(const NameScope& names, std::vector<Diagnostic>& diagnostics);

    // The project's `crs` once it is checked and valid, for positions written as [x, y].
    void setProjectCrs(const Value& crs) { projectCrs_ = crs; }
    // A crs was written but cannot be used (already reported): [x, y] positions stay quiet.
    void setProjectCrsInvalid() { projectCrsInvalid_ = true; }

    // The value as the model holds it, or nullopt after reporting why it does not fit.
    // `what` names the value in messages ("'height'", "param 'size'").
    std::optional<Value> coerce(Value value, const AttributeSchema& schema,
                                const std::string& what);
    // An angle in radians; a bare number is read as degrees (W0101).
    std::optional<double> coerceAngle(const Value& value, const std::string& what);

private:
    std::optional<Value> wrongType(const Value& value, const AttributeSchema& schema,
                                   const std::string& what);
    std::optional<Value> coerceNumber(Value value, const AttributeSchema& schema,
                                      const std::string& what);
    std::optional<Value> coerceGeo(Value value, const AttributeSchema& schema,
                                   const std::string& what);
    std::optional<Value> coerceObject(Value value, const AttributeSchema& schema,
                                      const std::string& what);
    std::optional<Value> coerceWord(Value value, const AttributeSchema& schema,
                                    const std::string& what);
    std::optional<Value> coerceReference(Value value, const AttributeSchema& schema,
                                         const std::string& what);
    std::optional<Value> coerceList(Value value, const AttributeSchema& schema,
                                    const std::string& what);

    const NameScope& names_;
    std::vector<Diagnostic>& diagnostics_;
    std::optional<Value> projectCrs_;
    bool projectCrsInvalid_ = false;
};

}  // namespace sylva::dsl
