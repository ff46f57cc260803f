#include "BlockChecker.h"

#include <algorithm>
#include <utility>

#include "DiagnosticText.h"
#include "MakeValue.h"
#include "sylva/dsl/EditDistance.h"
#include "sylva/dsl/ModelHash.h"

namespace sylva::dsl {

namespace {

bool isReferenceLike(const AttributeSchema& schema) {
    return schema.type == ValueType::Reference ||
           (schema.type == ValueType::List && schema.element == ValueType::Reference);
}

}  // namespace

BlockChecker::BlockChecker(ExpressionEvaluator& expressions, ValueChecker& values,
                           std::vector<Diagnostic>& diagnostics, bool lenient,
                           std::filesystem::path rootDirectory)
    : expressions_(expressions),
      values_(values),
      diagnostics_(diagnostics),
      lenient_(lenient),
      rootDirectory_(std::move(rootDirectory)) {}

Block BlockChecker::check(const BlockEntry& entry, const std::vector<Patch>& patches,
                          const Block* inherited) {
    const BlockNode& node = *entry.node;
    const KindSchema& kindSchema = *entry.schema;
    Block block;
    block.keyword = node.keyword;
    block.name = entry.scope + node.name;
    block.kind = node.kind;
    block.location = node.name.empty() ? node.keywordLocation : node.nameLocation;
    if (inherited) {
        block.attributes = inherited->attributes;
    }
    // The block's own attributes, then the patches (overrides, --set) that replace them.
    std::vector<Patch> items;
    for (const AttributeNode& attribute : node.attributes) {
        bool replaced = std::any_of(patches.begin(), patches.end(), [&](const Patch& patch) {
            return patch.attribute->name == attribute.name;
        });
        if (!replaced) {
            items.push_back({&attribute, entry.scope});
        }
    }
    const std::size_t ownCount = items.size();
    items.insert(items.end(), patches.begin(), patches.end());

    std::vector<std::string> written;
    std::vector<const AttributeNode*> seen;
    for (std::size_t index = 0; index < items.size(); ++index) {
        const AttributeNode& attribute = *items[index].attribute;
        if (index < ownCount) {
            auto first = std::find_if(seen.begin(), seen.end(), [&](const AttributeNode* other) {
                return other->name == attribute.name;
            });
            if (first != seen.end()) {
                addError(diagnostics_, "E0209", "duplicate attribute '" + attribute.name + "'",
                         attribute.nameLocation,
                         "'" + attribute.name + "' is already set in this block")
                    .notes.push_back({"first set here", (*first)->nameLocation});
                continue;
            }
            seen.push_back(&attribute);
        }
        written.push_back(attribute.name);
        applyAttribute(block, kindSchema, items[index]);
    }
    checkRequired(block, node, kindSchema, written, inherited);
    // An attribute written with an error gets no default: the error already speaks for it.
    fillDefaults(block, kindSchema, written);
    return block;
}

void BlockChecker::fillDefaults(Block& block, const KindSchema& kindSchema,
                                const std::vector<std::string>& written) {
    for (const AttributeSchema& attributeSchema : kindSchema.attributes) {
        if (!attributeSchema.defaultValue || block.find(attributeSchema.name) ||
            std::find(written.begin(), written.end(), attributeSchema.name) != written.end()) {
            continue;
        }
        Value value = *attributeSchema.defaultValue;
        value.location = block.location;
        block.attributes.push_back({attributeSchema.name, std::move(value), block.location});
    }
}

void BlockChecker::applyAttribute(Block& block, const KindSchema& kindSchema, const Patch& item) {
    const AttributeNode& attribute = *item.attribute;
    const AttributeSchema* attributeSchema = kindSchema.find(attribute.name);
    if (!attributeSchema) {
        reportUnknownAttribute(attribute, kindSchema);
        return;
    }
    std::optional<Value> value = expressions_.evaluate(
        *attribute.value, item.scope,
        isReferenceLike(*attributeSchema) ? referenceTarget(*attributeSchema) : "");
    if (!value) {
        return;
    }
    value = values_.coerce(std::move(*value), *attributeSchema, "'" + attribute.name + "'");
    if (!value) {
        return;
    }
    if (attribute.op != AssignOp::Set) {
        editList(block, attribute, *attributeSchema, *value);
        return;
    }
    auto existing = std::find_if(block.attributes.begin(), block.attributes.end(),
                                 [&](const Attribute& a) { return a.name == attribute.name; });
    if (existing != block.attributes.end()) {
        block.attributes.erase(existing);
    }
    rebasePath(attribute, *value);
    block.attributes.push_back({attribute.name, std::move(*value), attribute.nameLocation});
}

void BlockChecker::reportUnknownAttribute(const AttributeNode& attribute,
                                          const KindSchema& kindSchema) {
    std::vector<std::string> valid;
    for (const AttributeSchema& candidate : kindSchema.attributes) {
        valid.push_back(candidate.name);
    }
    std::string label = "not an attribute of " + describeBlock(kindSchema);
    Diagnostic& diagnostic =
        lenient_ ? addWarning(diagnostics_, "W0102",
                              "unknown attribute '" + attribute.name + "' ignored",
                              attribute.nameLocation, label)
                 : addError(diagnostics_, "E0208", "unknown attribute '" + attribute.name + "'",
                            attribute.nameLocation, label);
    if (auto match = closestMatch(attribute.name, valid)) {
        diagnostic.help.push_back("did you mean '" + *match + "'?");
    }
    diagnostic.help.push_back("valid attributes: " + join(valid));
}

void BlockChecker::editList(Block& block, const AttributeNode& attribute,
                            const AttributeSchema& attributeSchema, const Value& value) {
    const char* opText = attribute.op == AssignOp::Append ? "+=" : "-=";
    if (attributeSchema.type != ValueType::List) {
        addError(diagnostics_, "E0412", std::string("'") + opText + "' needs a list attribute",
                 attribute.opLocation,
                 "'" + attribute.name + "' is " + withArticle(expectedName(attributeSchema)))
            .help.push_back("write '" + attribute.name + " = ...' instead");
        return;
    }
    auto existing = std::find_if(block.attributes.begin(), block.attributes.end(),
                                 [&](const Attribute& a) { return a.name == attribute.name; });
    if (existing == block.attributes.end() || !existing->value.get<ValueList>()) {
        addError(diagnostics_, "E0412", std::string("'") + opText + "' needs an inherited list",
                 attribute.opLocation, "'" + attribute.name + "' has no inherited value to edit")
            .help.push_back("use '" + std::string(opText) +
                            "' in a scenario that extends one setting '" + attribute.name +
                            "', or write '" + attribute.name + " = [...]'");
        return;
    }
    ValueList list = *existing->value.get<ValueList>();
    for (const Value& item : *value.get<ValueList>()) {
        std::string text = canonicalText(item);
        auto same = std::find_if(list.begin(), list.end(),
                                 [&](const Value& other) { return canonicalText(other) == text; });
        if (attribute.op == AssignOp::Append) {
            list.push_back(item);
        } else if (same != list.end()) {
            list.erase(same);
        } else {
            addWarning(diagnostics_, "W0202",
                       "'-=' removes nothing: the inherited '" + attribute.name +
                           "' does not hold this value",
                       item.location, "not in the inherited list");
        }
    }
    existing->value = makeValue(std::move(list), attribute.value->location);
    existing->location = attribute.nameLocation;
}

void BlockChecker::checkRequired(const Block& block, const BlockNode& node,
                                 const KindSchema& kindSchema,
                                 const std::vector<std::string>& written, const Block* inherited) {
    for (const AttributeSchema& attributeSchema : kindSchema.attributes) {
        // A child scenario inherits what it omits; a broken parent is reported on its own.
        bool present =
            std::find(written.begin(), written.end(), attributeSchema.name) != written.end() ||
            (inherited && inherited->find(attributeSchema.name)) || !node.extends.empty();
        if (attributeSchema.required && !present) {
            std::string what = describeBlock(kindSchema);
            if (!node.name.empty()) {
                what += " '" + block.name + "'";
            }
            addError(diagnostics_, "E0405",
                     "missing required attribute '" + attributeSchema.name + "'", block.location,
                     what + " needs '" + attributeSchema.name + "'")
                .help.push_back(attributeSchema.name + ": " + attributeSchema.doc);
        }
    }
}

// Data paths resolve against the file that wrote them. The model holds them relative to
// the project file, so a `file = "dem.tif"` in lib/terrain.sylva becomes "lib/dem.tif".
void BlockChecker::rebasePath(const AttributeNode& attribute, Value& value) const {
    static const std::vector<std::string> kPathAttributes = {"file", "models", "disk_cache"};
    std::string* text = std::get_if<std::string>(&value.data);
    const auto& writer = attribute.nameLocation.file;
    if (!text || text->empty() || !writer || *writer == "<command line>" ||
        std::find(kPathAttributes.begin(), kPathAttributes.end(), attribute.name) ==
            kPathAttributes.end()) {
        return;
    }
    const std::filesystem::path written(*text);
    const std::filesystem::path writerDirectory = std::filesystem::path(*writer).parent_path();
    if (written.is_absolute() || text->find("://") != std::string::npos ||
        writerDirectory == rootDirectory_) {
        return;
    }
    std::filesystem::path relative = writerDirectory.lexically_relative(rootDirectory_);
    if (relative.empty()) {
        return;
    }
    std::string rebased = (relative / written).lexically_normal().generic_string();
    // Keep a trailing separator (a folder such as models = "plants/").
    if (text->back() == '/' && (rebased.empty() || rebased.back() != '/')) {
        rebased += '/';
    }
    *text = rebased;
}

}  // namespace sylva::dsl
