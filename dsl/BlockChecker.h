// Checks one block against its schema and turns it into a model Block: its own
// attributes, then the patches that replace them (scenario overrides, --set), each
// evaluated in the scope it is written in and coerced to the attribute's schema; `+=`
// and `-=` edit an inherited list; data paths are rebased onto the project file's
// folder; required attributes are checked and defaults filled in. Problems are E0208 /
// W0102 (unknown attribute; a warning when lenient), E0209 (duplicate), E0405
// (missing), E0412 (list edit without a list), W0202 (`-=` removing nothing).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "ExpressionEvaluator.h"
#include "NameScope.h"
#include "ValueChecker.h"
#include "sylva/core/model/ProjectModel.h"
#include "sylva/core/model/Schema.h"
#include "sylva/dsl/Diagnostic.h"

namespace sylva::dsl {

class BlockChecker {
public:
    // `rootDirectory`: the project file's folder, which the model's paths are relative to.
    BlockChecker(ExpressionEvaluator& expressions, ValueChecker& values,
                 std::vector<Diagnostic>& diagnostics, bool lenient,
                 std::filesystem::path rootDirectory);

    // The checked block. `inherited` (a scenario's parent) gives the attributes it starts
    // with. Attributes with errors are left out (and get no default).
    Block check(const BlockEntry& entry, const std::vector<Patch>& patches,
                const Block* inherited = nullptr);
    // Adds the schema's defaults for attributes the block neither has nor wrote.
    static void fillDefaults(Block& block, const KindSchema& schema,
                             const std::vector<std::string>& written = {});

private:
    // Checks and applies one written attribute to `block`.
    void applyAttribute(Block& block, const KindSchema& schema, const Patch& item);
    void reportUnknownAttribute(const AttributeNode& attribute, const KindSchema& schema);
    // `+=` / `-=` on the inherited list.
    void editList(Block& block, const AttributeNode& attribute, const AttributeSchema& schema,
                  const Value& value);
    void checkRequired(const Block& block, const BlockNode& node, const KindSchema& schema,
                       const std::vector<std::string>& written, const Block* inherited);
    // Data paths resolve against the file that wrote them (see BlockChecker.cpp).
    void rebasePath(const AttributeNode& attribute, Value& value) const;

    ExpressionEvaluator& expressions_;
    ValueChecker& values_;
    std::vector<Diagnostic>& diagnostics_;
    bool lenient_;
    std::filesystem::path rootDirectory_;
};

}  // namespace sylva::dsl
