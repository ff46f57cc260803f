#include "sylva/dsl/Resolver.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numbers>
#include <set>
#include <utility>

#include "sylva/core/geo/Geodesy.h"
#include "sylva/core/geo/ProjectedCoordinates.h"
#include "sylva/dsl/EditDistance.h"
#include "sylva/dsl/ModelHash.h"

namespace sylva::dsl {

namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

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

template <typename T>
Value makeValue(T data, const SourceLocation& location) {
    Value value;
    value.data = std::move(data);
    value.location = location;
    return value;
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

const std::vector<std::string> kParamTypes = {"number",     "length", "angle", "time",
                                              "percentage", "string", "bool",  "colour"};

bool paramTypeSchema(const std::string& type, AttributeSchema& schema) {
    static const std::pair<const char*, Dimension> kNumbers[] = {{"number", Dimension::None},
                                                                 {"length", Dimension::Length},
                                                                 {"angle", Dimension::Angle},
                                                                 {"time", Dimension::Time},
                                                                 {"percentage", Dimension::Ratio}};
    for (const auto& [name, dimension] : kNumbers) {
        if (type == name) {
            schema.type = ValueType::Number;
            schema.dimension = dimension;
            return true;
        }
    }
    if (type == "string") {
        schema.type = ValueType::String;
    } else if (type == "bool") {
        schema.type = ValueType::Bool;
    } else if (type == "colour" || type == "color") {
        schema.type = ValueType::Color;
    } else {
        return false;
    }
    return true;
}

bool isAnonymousKeyword(const std::string& keyword) {
    return keyword == "project" || keyword == "render";
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

std::vector<std::string> splitDots(const std::string& text) {
    std::vector<std::string> parts;
    std::size_t start = 0;
    while (true) {
        std::size_t dot = text.find('.', start);
        parts.push_back(text.substr(start, dot == std::string::npos ? dot : dot - start));
        if (dot == std::string::npos) {
            return parts;
        }
        start = dot + 1;
    }
}

const char* operatorText(char op) {
    switch (op) {
        case 'l':
            return "<=";
        case 'g':
            return ">=";
        case 'e':
            return "==";
        case 'n':
            return "!=";
        case '&':
            return "&&";
        case '|':
            return "||";
        case '<':
            return "<";
        case '>':
            return ">";
        case '%':
            return "%";
        default:
            return "?";
    }
}

}  // namespace

std::string formatQuantity(const Quantity& quantity) {
    switch (quantity.dimension) {
        case Dimension::None:
            return formatNumber(quantity.value);
        case Dimension::Length:
            return formatNumber(quantity.value) + "m";
        case Dimension::Angle:
            return formatNumber(quantity.value / kDegree) + "deg";
        case Dimension::Time:
            return formatNumber(quantity.value) + "s";
        case Dimension::Ratio:
            return formatNumber(quantity.value * 100.0) + "%";
        case Dimension::Pixels:
            return formatNumber(quantity.value) + "px";
    }
    return formatNumber(quantity.value);
}

Resolver::Resolver(const SchemaRegistry& schema, std::vector<Diagnostic>& diagnostics)
    : schema_(schema), diagnostics_(diagnostics) {}

std::optional<ProjectModel> Resolver::resolve(const FileNode& file,
                                              const std::vector<DefineNode>& defines,
                                              const std::filesystem::path& path) {
    std::vector<ProjectModel> models = resolve({ParsedUnit{&file, ""}}, defines, {}, path);
    if (models.empty()) {
        return std::nullopt;
    }
    return std::move(models.front());
}

std::vector<ProjectModel> Resolver::resolve(const std::vector<ParsedUnit>& units,
                                            const std::vector<DefineNode>& defines,
                                            const std::vector<SetNode>& sets,
                                            const std::filesystem::path& path,
                                            const ResolveOptions& options) {
    options_ = options;
    rootDirectory_ = path.parent_path();
    std::size_t statements = 0;
    for (const ParsedUnit& unit : units) {
        statements += unit.file->statements.size();
    }
    declarations_.reserve(statements);
    for (const ParsedUnit& unit : units) {
        for (const Statement& statement : unit.file->statements) {
            declare(statement, unit.scope);
        }
    }
    applyDefines(defines);
    for (const SetNode& set : sets) {
        auto found = names_.find(set.block);
        bool known = set.block == "project" || set.block == "render" ||
                     (found != names_.end() && declarations_[found->second].block);
        if (!known) {
            std::vector<std::string> blocks = {"project", "render"};
            for (const Declaration& declaration : declarations_) {
                if (declaration.block) {
                    blocks.push_back(declaration.name);
                }
            }
            Diagnostic& diagnostic =
                addError(diagnostics_, "E0213", "unknown block '" + set.block + "' in --set",
                         set.blockLocation, "no block named '" + set.block + "'");
            if (auto match = closestMatch(set.block, blocks)) {
                diagnostic.help.push_back("did you mean '" + *match + "'?");
            }
            diagnostic.help.push_back(
                "write --set BLOCK.ATTRIBUTE=VALUE, e.g. --set render.exposure=2");
            continue;
        }
        setPatches_[set.block].push_back({&set.attribute, ""});
    }
    for (Declaration& declaration : declarations_) {
        if (declaration.keyword == "param") {
            evaluateParam(declaration, declaration.location);
        }
    }
    // --set on a project/render block the files omit still has to be checked.
    for (const char* keyword : {"project", "render"}) {
        const BlockNode* written = std::string_view(keyword) == "project" ? project_ : render_;
        const KindSchema* kindSchema = schema_.find(keyword);
        if (!written && kindSchema && setPatches_.count(keyword)) {
            auto node = std::make_unique<BlockNode>();
            node->keyword = keyword;
            node->keywordLocation = setPatches_[keyword].front().attribute->nameLocation;
            blocks_.push_back({node.get(), kindSchema, ""});
            implicit_.push_back(std::move(node));
        }
    }

    ProjectModel model;
    model.file = path;
    // The project block first: its `crs` is needed to read positions written in
    // projected coordinates anywhere else.
    std::vector<const BlockEntry*> ordered;
    for (const BlockEntry& entry : blocks_) {
        if (entry.node->keyword == "project") {
            ordered.push_back(&entry);
        }
    }
    for (const BlockEntry& entry : blocks_) {
        if (entry.node->keyword != "project") {
            ordered.push_back(&entry);
        }
    }
    for (const BlockEntry* orderedEntry : ordered) {
        const BlockEntry& entry = *orderedEntry;
        if (entry.node->keyword == "scenario") {
            continue;  // after all other blocks: scenarios inherit from each other
        }
        const std::string& key =
            entry.node->name.empty() ? entry.node->keyword : entry.scope + entry.node->name;
        auto patches = setPatches_.find(key);
        std::optional<Block> block = checkBlock(
            entry, patches == setPatches_.end() ? std::vector<Patch>{} : patches->second);
        if (!block) {
            continue;
        }
        const std::string& keyword = block->keyword;
        if (keyword == "source") {
            model.sources.push_back(std::move(*block));
        } else if (keyword == "camera") {
            model.cameras.push_back(std::move(*block));
        } else if (keyword == "views") {
            model.views.push_back(std::move(*block));
        } else if (keyword == "compare") {
            model.compares.push_back(std::move(*block));
        } else if (keyword == "blend") {
            model.blends.push_back(std::move(*block));
        } else if (keyword == "path") {
            model.paths.push_back(std::move(*block));
        } else if (keyword == "project") {
            model.project = std::move(*block);
            if (const Attribute* crs = model.project.find("crs")) {
                const std::string* text = crs->value.get<std::string>();
                if (text != nullptr && !text->empty()) {
                    if (Status valid = ProjectedCoordinates::validate(*text); !valid) {
                        projectCrsInvalid_ = true;  // reported once, here
                        addError(diagnostics_, "E0414", valid.error().message, crs->value.location,
                                 "not a coordinate reference system GDAL/PROJ can convert to WGS84");
                    } else {
                        projectCrs_ = crs->value;
                    }
                }
            }
        } else if (keyword == "render") {
            model.render = std::move(*block);
        }
    }
    std::vector<Declaration*> scenarios;
    for (Declaration& declaration : declarations_) {
        if (declaration.keyword == "scenario" && declaration.schema) {
            resolveScenario(declaration);
            if (declaration.scenarioBlock) {
                model.scenarios.push_back(*declaration.scenarioBlock);
                scenarios.push_back(&declaration);
            }
        }
    }
    // project and render exist even when the file omits them.
    for (Block* block : {&model.project, &model.render}) {
        if (block->keyword.empty()) {
            block->keyword = block == &model.project ? "project" : "render";
            block->location.file = std::make_shared<const std::string>(path.string());
            if (const KindSchema* kindSchema = schema_.find(block->keyword)) {
                fillDefaults(*block, *kindSchema);
            }
        }
    }

    for (const Declaration& declaration : declarations_) {
        if (declaration.keyword != "param") {
            continue;
        }
        if (!declaration.used) {
            addWarning(diagnostics_, "W0201", "unused param '" + declaration.name + "'",
                       declaration.location, "declared here but never used");
        }
        if (!declaration.value) {
            continue;
        }
        Block param;
        param.keyword = "param";
        param.name = declaration.name;
        param.kind = declaration.param->type;
        param.location = declaration.location;
        param.attributes.push_back({"value", *declaration.value, declaration.location});
        if (!declaration.param->doc.empty()) {
            param.attributes.push_back({"doc",
                                        makeValue(declaration.param->doc, declaration.location),
                                        declaration.location});
        }
        model.params.push_back(std::move(param));
    }

    std::vector<ProjectModel> models;
    computeContentHashes(model);
    if (scenarios.empty()) {
        findCycles(model.sources);
        models.push_back(std::move(model));
    }
    for (Declaration* scenario : scenarios) {
        ProjectModel scenarioModel = model;
        scenarioModel.scenario = scenario->name;
        // The overrides of this scenario (inherited ones first), by target block.
        std::map<std::string, std::vector<Patch>> overrides;
        for (std::size_t i = 0; i < scenario->overrideAttributes.size(); ++i) {
            const auto& [target, attribute] = scenario->overrideAttributes[i];
            overrides[target].push_back({attribute, scenario->overrideScopes[i]});
        }
        for (const auto& entryPair : overrides) {
            const std::string& target = entryPair.first;
            const std::vector<Patch>& patches = entryPair.second;
            const Declaration& declaration = declarations_[names_.find(target)->second];
            std::vector<Block>& blocks =
                declaration.keyword == "source" ? scenarioModel.sources : scenarioModel.cameras;
            auto found = std::find_if(blocks.begin(), blocks.end(),
                                      [&](const Block& block) { return block.name == target; });
            if (found == blocks.end()) {
                continue;  // the block itself has errors, already reported
            }
            std::vector<Patch> all;
            if (auto setFound = setPatches_.find(target); setFound != setPatches_.end()) {
                all = setFound->second;
            }
            all.insert(all.end(), patches.begin(), patches.end());
            BlockEntry entry{declaration.block, declaration.schema, declaration.scope};
            if (std::optional<Block> block = checkBlock(entry, all)) {
                *found = std::move(*block);
            }
        }
        // Without overrides the graph is the base graph, checked once.
        if (!overrides.empty() || scenario == scenarios.front()) {
            findCycles(scenarioModel.sources);
        }
        std::vector<std::string> changed;
        for (const auto& entryPair : overrides) {
            changed.push_back(entryPair.first);
        }
        computeContentHashes(scenarioModel, &changed);
        models.push_back(std::move(scenarioModel));
    }
    if (hasErrors(diagnostics_)) {
        return {};
    }
    return models;
}

void Resolver::resolveScenario(Declaration& scenario) {
    if (scenario.scenarioState == 2) {
        return;
    }
    scenario.scenarioState = 1;
    const BlockNode& node = *scenario.block;
    const Block* inherited = nullptr;
    if (!node.extends.empty()) {
        std::vector<std::string> fields;
        Declaration* parent = lookup(scenario.scope, node.extends, &fields);
        if (!parent || !fields.empty()) {
            Diagnostic& diagnostic =
                addError(diagnostics_, "E0201", "unknown scenario '" + node.extends + "'",
                         node.extendsLocation, "no scenario named '" + node.extends + "'");
            std::vector<std::string> candidates;
            for (const Declaration& declaration : declarations_) {
                if (declaration.keyword == "scenario") {
                    candidates.push_back(declaration.name);
                }
            }
            if (auto match = closestMatch(node.extends, candidates)) {
                diagnostic.help.push_back("did you mean '" + *match + "'?");
            }
        } else if (parent->keyword != "scenario") {
            addError(diagnostics_, "E0406", "expected scenario, found " + parent->keyword,
                     node.extendsLocation,
                     "'" + parent->name + "' is " + withArticle(parent->keyword));
        } else if (parent->scenarioState == 1) {
            bool self = parent == &scenario;
            addError(diagnostics_, "E0303",
                     self ? "scenario '" + scenario.name + "' extends itself"
                          : "scenarios '" + scenario.name + "' and '" + parent->name +
                                "' extend each other",
                     node.extendsLocation,
                     "'" + scenario.name + "' extends '" + parent->name + "' here")
                .help.push_back(
                    "a scenario cannot inherit from itself, directly or through others");
        } else {
            resolveScenario(*parent);
            if (parent->scenarioBlock) {
                inherited = &*parent->scenarioBlock;
                scenario.overrideAttributes = parent->overrideAttributes;
                scenario.overrideScopes = parent->overrideScopes;
            } else {
                scenario.scenarioState = 2;
                return;  // the parent has errors; do not pile more on
            }
        }
    }
    BlockEntry entry{scenario.block, scenario.schema, scenario.scope};
    auto patches = setPatches_.find(scenario.name);
    scenario.scenarioBlock = checkBlock(
        entry, patches == setPatches_.end() ? std::vector<Patch>{} : patches->second, inherited);
    for (const OverrideNode& override : node.overrides) {
        std::vector<std::string> fields;
        Declaration* target = lookup(scenario.scope, override.target, &fields);
        if (!target || !fields.empty()) {
            Diagnostic& diagnostic =
                addError(diagnostics_, "E0201", "unknown reference '@" + override.target + "'",
                         override.targetLocation, "no source named '" + override.target + "'");
            std::vector<std::string> candidates;
            for (const Declaration& declaration : declarations_) {
                if (declaration.keyword == "source" || declaration.keyword == "camera") {
                    candidates.push_back(declaration.name);
                }
            }
            if (auto match = closestMatch(override.target, candidates)) {
                diagnostic.help.push_back("did you mean '@" + *match + "' (defined at " +
                                          shortLocation(declarations_[names_[*match]].location) +
                                          ")?");
            }
            continue;
        }
        if (target->keyword != "source" && target->keyword != "camera") {
            addError(diagnostics_, "E0406", "expected source or camera, found " + target->keyword,
                     override.targetLocation, "only sources and cameras can be overridden");
            continue;
        }
        for (const AttributeNode& attribute : override.attributes) {
            scenario.overrideAttributes.emplace_back(target->name, &attribute);
            scenario.overrideScopes.push_back(scenario.scope);
        }
    }
    scenario.scenarioState = 2;
}

// Data paths resolve against the file that wrote them. The model holds them relative to
// the project file, so a `file = "dem.tif"` in lib/terrain.sylva becomes "lib/dem.tif".
void Resolver::rebasePath(const AttributeNode& attribute, Value& value) const {
    static const std::vector<std::string> kPathAttributes = {"file", "models"};
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

Resolver::Declaration* Resolver::lookup(const std::string& scope, const std::string& written,
                                        std::vector<std::string>* fields) {
    std::vector<std::string> parts = splitDots(written);
    for (std::size_t n = parts.size(); n >= 1; --n) {
        std::string candidate = scope;
        for (std::size_t i = 0; i < n; ++i) {
            candidate += (i > 0 ? "." : "") + parts[i];
        }
        auto found = names_.find(candidate);
        if (found != names_.end()) {
            if (fields) {
                fields->assign(parts.begin() + static_cast<std::ptrdiff_t>(n), parts.end());
            }
            return &declarations_[found->second];
        }
    }
    return nullptr;
}

bool Resolver::addName(Declaration declaration) {
    auto found = names_.find(declaration.name);
    if (found != names_.end()) {
        const Declaration& first = declarations_[found->second];
        addError(diagnostics_, "E0202", "duplicate name '" + declaration.name + "'",
                 declaration.location, "'" + declaration.name + "' is already defined")
            .notes.push_back({"'" + declaration.name + "' first defined here", first.location});
        return false;
    }
    names_.emplace(declaration.name, declarations_.size());
    declarations_.push_back(std::move(declaration));
    return true;
}

void Resolver::declare(const Statement& statement, const std::string& scope) {
    if (std::holds_alternative<ImportNode>(statement)) {
        return;  // the loader follows imports; their files arrive as units of their own
    }
    if (const auto* param = std::get_if<ParamNode>(&statement)) {
        Declaration declaration;
        declaration.keyword = "param";
        declaration.name = scope + param->name;
        declaration.scope = scope;
        declaration.valueScope = scope;
        declaration.location = param->nameLocation;
        declaration.param = param;
        declaration.valueExpr = param->defaultValue.get();
        addName(std::move(declaration));
        return;
    }
    const auto& block = std::get<BlockNode>(statement);
    std::vector<std::string> keywords;
    for (const KindSchema& kindSchema : schema_.all()) {
        if (std::find(keywords.begin(), keywords.end(), kindSchema.keyword) == keywords.end()) {
            keywords.push_back(kindSchema.keyword);
        }
    }
    if (std::find(keywords.begin(), keywords.end(), block.keyword) == keywords.end()) {
        Diagnostic& diagnostic =
            addError(diagnostics_, "E0203", "unknown block keyword '" + block.keyword + "'",
                     block.keywordLocation, "not a block keyword");
        if (auto match = closestMatch(block.keyword, keywords)) {
            diagnostic.help.push_back("did you mean '" + *match + "'?");
        }
        diagnostic.help.push_back("block keywords are: param, " + join(keywords));
        return;
    }
    const std::string& keyword = block.keyword;
    if (!block.extends.empty() && keyword != "scenario") {
        addError(diagnostics_, "E0214", "'" + keyword + "' blocks cannot extend others",
                 block.extendsLocation, "only scenarios use 'extends'");
    }
    if (!block.overrides.empty() && keyword != "scenario") {
        addError(diagnostics_, "E0214", "'override' outside of a scenario",
                 block.overrides.front().targetLocation, "only scenarios override blocks")
            .help.push_back("write the attribute directly, or move the override into a scenario");
    }
    const KindSchema* kindSchema = nullptr;
    if (keyword == "source") {
        if (block.name.empty()) {
            addError(diagnostics_, "E0205", "source needs a name and a kind", block.keywordLocation,
                     "write 'source NAME : KIND { ... }'");
            return;
        }
        if (block.kind.empty()) {
            addError(diagnostics_, "E0205", "source '" + block.name + "' needs a kind",
                     block.nameLocation, "write 'source " + block.name + " : KIND { ... }'");
        } else {
            kindSchema = schema_.find("source", block.kind);
            if (!kindSchema) {
                std::vector<std::string> kinds = schema_.sourceKinds();
                Diagnostic& diagnostic =
                    addError(diagnostics_, "E0204", "unknown source kind '" + block.kind + "'",
                             block.kindLocation, "not a source kind");
                if (auto match = closestMatch(block.kind, kinds)) {
                    diagnostic.help.push_back("did you mean '" + *match + "'?");
                }
                diagnostic.help.push_back("source kinds are: " + join(kinds));
            }
        }
    } else {
        kindSchema = schema_.find(keyword);
        if (!block.kind.empty()) {
            addError(diagnostics_, "E0205", "'" + keyword + "' blocks have no kind",
                     block.kindLocation, "only sources have a kind");
            return;
        }
        if (isAnonymousKeyword(keyword)) {
            if (!block.name.empty()) {
                addError(diagnostics_, "E0205", "'" + keyword + "' block takes no name",
                         block.nameLocation, "remove this name");
                return;
            }
            const BlockNode*& first = keyword == "project" ? project_ : render_;
            if (first) {
                addError(diagnostics_, "E0206", "duplicate '" + keyword + "' block",
                         block.keywordLocation, "second '" + keyword + "' block")
                    .notes.push_back(
                        {"first '" + keyword + "' block here", first->keywordLocation});
                return;
            }
            first = &block;
            blocks_.push_back({&block, kindSchema, scope});
            return;
        }
        if (block.name.empty()) {
            addError(diagnostics_, "E0205", "'" + keyword + "' block needs a name",
                     block.keywordLocation, "write '" + keyword + " NAME { ... }'");
            return;
        }
    }
    Declaration declaration;
    declaration.keyword = keyword;
    declaration.name = scope + block.name;
    declaration.scope = scope;
    declaration.kind = block.kind;
    declaration.location = block.nameLocation;
    declaration.block = &block;
    declaration.schema = kindSchema;
    if (addName(std::move(declaration)) && kindSchema) {
        blocks_.push_back({&block, kindSchema, scope});
    }
}

void Resolver::applyDefines(const std::vector<DefineNode>& defines) {
    for (const DefineNode& define : defines) {
        auto found = names_.find(define.name);
        if (found == names_.end() || declarations_[found->second].keyword != "param") {
            Diagnostic& diagnostic =
                addError(diagnostics_, "E0207", "undeclared param '" + define.name + "'",
                         define.nameLocation, "no param named '" + define.name + "'");
            std::vector<std::string> params;
            for (const Declaration& declaration : declarations_) {
                if (declaration.keyword == "param") {
                    params.push_back(declaration.name);
                }
            }
            if (auto match = closestMatch(define.name, params)) {
                diagnostic.help.push_back("did you mean '" + *match + "' (defined at " +
                                          shortLocation(declarations_[names_[*match]].location) +
                                          ")?");
            }
            diagnostic.help.push_back("-D sets only params declared with 'param'");
            continue;
        }
        if (define.value) {
            declarations_[found->second].valueExpr = define.value.get();
            declarations_[found->second].valueScope = "";
        } else {
            // The value did not parse (already reported); keep the param quiet.
            declarations_[found->second].valueExpr = nullptr;
            declarations_[found->second].state = 2;
        }
    }
}

std::optional<Value> Resolver::evaluateParam(Declaration& param, const SourceLocation& use) {
    if (param.state == 2) {
        return param.value;
    }
    if (param.state == 1) {
        addError(diagnostics_, "E0302", "param '" + param.name + "' depends on itself", use,
                 "used while computing its own value");
        return std::nullopt;
    }
    param.state = 1;
    std::optional<Value> value;
    AttributeSchema typeSchema;
    bool typed = !param.param->type.empty();
    if (typed && !paramTypeSchema(param.param->type, typeSchema)) {
        Diagnostic& diagnostic =
            addError(diagnostics_, "E0212", "unknown param type '" + param.param->type + "'",
                     param.param->typeLocation, "not a type");
        if (auto match = closestMatch(param.param->type, kParamTypes)) {
            diagnostic.help.push_back("did you mean '" + *match + "'?");
        }
        diagnostic.help.push_back("types are: " + join(kParamTypes));
    } else if (!param.valueExpr) {
        addError(diagnostics_, "E0409", "param '" + param.name + "' has no value", param.location,
                 "declared without a default")
            .help.push_back("give it a default ('param " + param.name +
                            " = ...') or set it with -D " + param.name + "=...");
    } else {
        std::string saved = std::exchange(scope_, param.valueScope);
        value = evaluate(*param.valueExpr, "");
        scope_ = saved;
        if (value && typed) {
            value = coerce(std::move(*value), typeSchema, "param '" + param.name + "'");
        }
    }
    param.state = 2;
    param.value = value;
    return value;
}

std::string Resolver::describeBlock(const KindSchema& kindSchema) const {
    return kindSchema.keyword == "source" ? kindSchema.kind + " source" : kindSchema.keyword;
}

std::optional<Block> Resolver::checkBlock(const BlockEntry& entry,
                                          const std::vector<Patch>& patches,
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
        const AttributeSchema* attributeSchema = kindSchema.find(attribute.name);
        if (!attributeSchema) {
            std::vector<std::string> valid;
            for (const AttributeSchema& candidate : kindSchema.attributes) {
                valid.push_back(candidate.name);
            }
            std::string label = "not an attribute of " + describeBlock(kindSchema);
            Diagnostic& diagnostic =
                options_.lenient
                    ? addWarning(diagnostics_, "W0102",
                                 "unknown attribute '" + attribute.name + "' ignored",
                                 attribute.nameLocation, label)
                    : addError(diagnostics_, "E0208", "unknown attribute '" + attribute.name + "'",
                               attribute.nameLocation, label);
            if (auto match = closestMatch(attribute.name, valid)) {
                diagnostic.help.push_back("did you mean '" + *match + "'?");
            }
            diagnostic.help.push_back("valid attributes: " + join(valid));
            continue;
        }
        bool referenceLike = attributeSchema->type == ValueType::Reference ||
                             (attributeSchema->type == ValueType::List &&
                              attributeSchema->element == ValueType::Reference);
        std::string saved = std::exchange(scope_, items[index].scope);
        std::optional<Value> value =
            evaluate(*attribute.value, referenceLike ? referenceTarget(*attributeSchema) : "");
        scope_ = saved;
        if (!value) {
            continue;
        }
        value = coerce(std::move(*value), *attributeSchema, "'" + attribute.name + "'");
        if (!value) {
            continue;
        }
        auto existing = std::find_if(block.attributes.begin(), block.attributes.end(),
                                     [&](const Attribute& a) { return a.name == attribute.name; });
        if (attribute.op != AssignOp::Set) {
            const char* opText = attribute.op == AssignOp::Append ? "+=" : "-=";
            if (attributeSchema->type != ValueType::List) {
                addError(
                    diagnostics_, "E0412", std::string("'") + opText + "' needs a list attribute",
                    attribute.opLocation,
                    "'" + attribute.name + "' is " + withArticle(expectedName(*attributeSchema)))
                    .help.push_back("write '" + attribute.name + " = ...' instead");
                continue;
            }
            if (existing == block.attributes.end() || !existing->value.get<ValueList>()) {
                addError(
                    diagnostics_, "E0412", std::string("'") + opText + "' needs an inherited list",
                    attribute.opLocation, "'" + attribute.name + "' has no inherited value to edit")
                    .help.push_back("use '" + std::string(opText) +
                                    "' in a scenario that extends one setting '" + attribute.name +
                                    "', or write '" + attribute.name + " = [...]'");
                continue;
            }
            ValueList list = *existing->value.get<ValueList>();
            for (const Value& item : *value->get<ValueList>()) {
                std::string text = canonicalText(item);
                auto same = std::find_if(list.begin(), list.end(), [&](const Value& other) {
                    return canonicalText(other) == text;
                });
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
            Value merged = makeValue(std::move(list), attribute.value->location);
            existing->value = std::move(merged);
            existing->location = attribute.nameLocation;
            continue;
        }
        if (existing != block.attributes.end()) {
            block.attributes.erase(existing);
        }
        rebasePath(attribute, *value);
        block.attributes.push_back({attribute.name, std::move(*value), attribute.nameLocation});
    }
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
    // An attribute written with an error gets no default: the error already speaks for it.
    fillDefaults(block, kindSchema, written);
    return block;
}

void Resolver::fillDefaults(Block& block, const KindSchema& kindSchema,
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

std::optional<Value> Resolver::evaluate(const Expr& expr, const std::string& expectedTarget) {
    switch (expr.kind) {
        case Expr::Kind::Number:
            return makeValue(Quantity{expr.number, expr.dimension}, expr.location);
        case Expr::Kind::String:
            return makeValue(expr.text, expr.location);
        case Expr::Kind::Color:
            return makeValue(expr.color, expr.location);
        case Expr::Kind::Bool:
            return makeValue(expr.boolean, expr.location);
        case Expr::Kind::Word:
            return makeValue(Word{expr.text}, expr.location);
        case Expr::Kind::DateTime:
            return makeValue(expr.text, expr.location);
        case Expr::Kind::Conditional: {
            std::optional<Value> condition = evaluate(*expr.children[0], "");
            std::optional<Value> then = evaluate(*expr.children[1], expectedTarget);
            std::optional<Value> otherwise = evaluate(*expr.children[2], expectedTarget);
            if (!condition || !then || !otherwise) {
                return std::nullopt;
            }
            const bool* flag = condition->get<bool>();
            if (!flag) {
                addError(diagnostics_, "E0402", "expected bool, found " + condition->typeName(),
                         condition->location, "a condition must be true or false");
                return std::nullopt;
            }
            Value chosen = *flag ? std::move(*then) : std::move(*otherwise);
            return chosen;
        }
        case Expr::Kind::Index: {
            std::optional<Value> container = evaluate(*expr.children[0], expectedTarget);
            std::optional<Value> index = evaluate(*expr.children[1], "");
            if (!container || !index) {
                return std::nullopt;
            }
            if (const std::string* key = index->get<std::string>()) {
                return fieldOf(*container, *key, expr.location);
            }
            const ValueList* list = container->get<ValueList>();
            const Quantity* position = index->get<Quantity>();
            if (!list || !position || position->dimension != Dimension::None) {
                addError(diagnostics_, "E0402",
                         "cannot index " + withArticle(container->typeName()) + " with " +
                             withArticle(index->typeName()),
                         expr.location, "write list[number] or object[\"key\"]");
                return std::nullopt;
            }
            double at = position->value;
            if (at < 0 || at != std::floor(at) || at >= static_cast<double>(list->size())) {
                addError(diagnostics_, "E0404", "index out of range", index->location,
                         formatNumber(at) + " is not in [0, " + std::to_string(list->size()) + ")");
                return std::nullopt;
            }
            Value element = (*list)[static_cast<std::size_t>(at)];
            element.location = expr.location;
            return element;
        }
        case Expr::Kind::Field: {
            std::optional<Value> object = evaluate(*expr.children[0], "");
            if (!object) {
                return std::nullopt;
            }
            return fieldOf(*object, expr.text, expr.location);
        }
        case Expr::Kind::Reference:
            return evaluateReference(expr, expectedTarget);
        case Expr::Kind::Unary:
            return evaluateUnary(expr);
        case Expr::Kind::Binary:
            return evaluateBinary(expr);
        case Expr::Kind::Call:
            return evaluateCall(expr);
        case Expr::Kind::List: {
            ValueList list;
            bool ok = true;
            for (const ExprPtr& child : expr.children) {
                std::optional<Value> element = evaluate(*child, expectedTarget);
                if (element) {
                    list.push_back(std::move(*element));
                } else {
                    ok = false;
                }
            }
            return ok ? std::optional<Value>(makeValue(std::move(list), expr.location))
                      : std::nullopt;
        }
        case Expr::Kind::Object: {
            ValueObject object;
            bool ok = true;
            for (std::size_t i = 0; i < expr.children.size(); ++i) {
                const std::string& key = expr.keys[i].first;
                const SourceLocation& keyLocation = expr.keys[i].second;
                auto first = std::find_if(object.begin(), object.end(),
                                          [&](const auto& entry) { return entry.first == key; });
                if (first != object.end()) {
                    addError(diagnostics_, "E0209", "duplicate key '" + key + "'", keyLocation,
                             "'" + key + "' is already set in this object")
                        .notes.push_back({"first set here", first->second.location});
                    ok = false;
                    continue;
                }
                std::optional<Value> value = evaluate(*expr.children[i], "");
                if (value) {
                    object.emplace_back(key, std::move(*value));
                } else {
                    ok = false;
                }
            }
            return ok ? std::optional<Value>(makeValue(std::move(object), expr.location))
                      : std::nullopt;
        }
    }
    return std::nullopt;
}

std::optional<Value> Resolver::evaluateReference(const Expr& expr,
                                                 const std::string& expectedTarget) {
    const std::string written = expr.text + (expr.field.empty() ? "" : "." + expr.field);
    std::vector<std::string> fields;
    Declaration* found = lookup(scope_, written, &fields);
    if (!found) {
        Diagnostic& diagnostic =
            addError(diagnostics_, "E0201", "unknown reference '@" + written + "'", expr.location,
                     (expectedTarget.empty() ? "nothing" : "no " + expectedTarget) + " named '" +
                         written + "'");
        std::vector<std::string> preferred;
        std::vector<std::string> all;
        for (const Declaration& declaration : declarations_) {
            if (declaration.name.compare(0, scope_.size(), scope_) != 0) {
                continue;
            }
            std::string local = declaration.name.substr(scope_.size());
            all.push_back(local);
            if (declaration.keyword == expectedTarget) {
                preferred.push_back(local);
            }
        }
        std::optional<std::string> match = closestMatch(written, preferred);
        if (!match) {
            match = closestMatch(written, all);
        }
        if (match) {
            diagnostic.help.push_back(
                "did you mean '@" + *match + "' (defined at " +
                shortLocation(declarations_[names_[scope_ + *match]].location) + ")?");
        }
        return std::nullopt;
    }
    Declaration& declaration = *found;
    std::optional<Value> value;
    std::size_t next = 0;
    if (declaration.keyword == "param") {
        declaration.used = true;
        value = evaluateParam(declaration, expr.location);
    } else if (fields.empty()) {
        return makeValue(Reference{declaration.keyword, declaration.name}, expr.location);
    } else {
        value = evaluateBlockField(declaration, fields[0], expr.location);
        next = 1;
    }
    for (; value && next < fields.size(); ++next) {
        value = fieldOf(*value, fields[next], expr.location);
    }
    if (value) {
        value->location = expr.location;
    }
    return value;
}

std::optional<Value> Resolver::evaluateBlockField(Declaration& declaration,
                                                  const std::string& field,
                                                  const SourceLocation& location) {
    if (!declaration.schema || !declaration.block) {
        return std::nullopt;  // the block's own error speaks for it
    }
    const AttributeSchema* attributeSchema = declaration.schema->find(field);
    if (!attributeSchema) {
        std::vector<std::string> valid;
        for (const AttributeSchema& candidate : declaration.schema->attributes) {
            valid.push_back(candidate.name);
        }
        Diagnostic& diagnostic = addError(
            diagnostics_, "E0210", "unknown field '" + field + "' of '" + declaration.name + "'",
            location,
            "'" + declaration.name + "' is " + withArticle(describeBlock(*declaration.schema)) +
                " without '" + field + "'");
        if (auto match = closestMatch(field, valid)) {
            diagnostic.help.push_back("did you mean '" + *match + "'?");
        }
        diagnostic.help.push_back("fields are: " + join(valid));
        return std::nullopt;
    }
    const AttributeNode* written = nullptr;
    std::string scope = declaration.scope;
    for (const AttributeNode& attribute : declaration.block->attributes) {
        if (attribute.name == field && attribute.op == AssignOp::Set) {
            written = &attribute;
        }
    }
    if (auto setFound = setPatches_.find(declaration.name); setFound != setPatches_.end()) {
        for (const Patch& patch : setFound->second) {
            if (patch.attribute->name == field) {
                written = patch.attribute;
                scope = patch.scope;
            }
        }
    }
    if (!written) {
        if (attributeSchema->defaultValue) {
            Value value = *attributeSchema->defaultValue;
            value.location = location;
            return value;
        }
        addError(diagnostics_, "E0210", "'" + declaration.name + "' has no '" + field + "'",
                 location, "'" + field + "' is not set and has no default");
        return std::nullopt;
    }
    const std::string key = declaration.name + "." + field;
    if (std::find(evaluatingFields_.begin(), evaluatingFields_.end(), key) !=
        evaluatingFields_.end()) {
        addError(diagnostics_, "E0302", "'@" + key + "' depends on itself", location,
                 "used while computing its own value");
        return std::nullopt;
    }
    evaluatingFields_.push_back(key);
    std::string saved = std::exchange(scope_, scope);
    bool referenceLike = attributeSchema->type == ValueType::Reference ||
                         (attributeSchema->type == ValueType::List &&
                          attributeSchema->element == ValueType::Reference);
    std::optional<Value> value =
        evaluate(*written->value, referenceLike ? referenceTarget(*attributeSchema) : "");
    if (value) {
        value = coerce(std::move(*value), *attributeSchema, "'" + field + "'");
    }
    scope_ = saved;
    evaluatingFields_.pop_back();
    return value;
}

std::optional<Value> Resolver::fieldOf(const Value& value, const std::string& field,
                                       const SourceLocation& location) {
    if (const GeoPosition* geo = value.get<GeoPosition>()) {
        if (field == "latitude" || field == "lat") {
            return makeValue(Quantity{geo->latitude, Dimension::Angle}, location);
        }
        if (field == "longitude" || field == "lon") {
            return makeValue(Quantity{geo->longitude, Dimension::Angle}, location);
        }
        if (field == "height" && geo->height) {
            return makeValue(Quantity{*geo->height, Dimension::Length}, location);
        }
    } else if (const ValueObject* object = value.get<ValueObject>()) {
        for (const auto& [key, item] : *object) {
            if (key == field) {
                Value result = item;
                result.location = location;
                return result;
            }
        }
    }
    addError(diagnostics_, "E0210",
             "unknown field '" + field + "' of " + withArticle(value.typeName()), location,
             value.get<GeoPosition>() ? "geo positions have latitude, longitude and height"
                                      : "no field named '" + field + "'");
    return std::nullopt;
}

std::optional<Value> Resolver::evaluateUnary(const Expr& expr) {
    std::optional<Value> operand = evaluate(*expr.children[0], "");
    if (!operand) {
        return std::nullopt;
    }
    if (expr.op == '!') {
        const bool* flag = operand->get<bool>();
        if (!flag) {
            addError(diagnostics_, "E0402", "expected bool, found " + operand->typeName(),
                     expr.location, "'!' works on true and false only");
            return std::nullopt;
        }
        return makeValue(!*flag, expr.location);
    }
    const Quantity* quantity = operand->get<Quantity>();
    if (!quantity) {
        addError(diagnostics_, "E0401", "cannot negate " + withArticle(operand->typeName()),
                 expr.location, "only numbers and quantities have a sign");
        return std::nullopt;
    }
    Quantity result = *quantity;
    if (expr.op == '-') {
        result.value = -result.value;
    }
    return makeValue(result, expr.location);
}

std::optional<Value> Resolver::evaluateBinary(const Expr& expr) {
    std::optional<Value> left = evaluate(*expr.children[0], "");
    std::optional<Value> right = evaluate(*expr.children[1], "");
    if (!left || !right) {
        return std::nullopt;
    }
    if (expr.op == '&' || expr.op == '|') {
        const bool* a = left->get<bool>();
        const bool* b = right->get<bool>();
        if (!a || !b) {
            const Value& wrong = a ? *right : *left;
            addError(diagnostics_, "E0402", "expected bool, found " + wrong.typeName(),
                     wrong.location,
                     std::string("'") + operatorText(expr.op) + "' works on true and false only");
            return std::nullopt;
        }
        return makeValue(expr.op == '&' ? (*a && *b) : (*a || *b), expr.location);
    }
    if (expr.op == 'e' || expr.op == 'n') {
        const Quantity* a = left->get<Quantity>();
        const Quantity* b = right->get<Quantity>();
        bool comparable =
            left->data.index() == right->data.index() && (!a || a->dimension == b->dimension);
        if (!comparable) {
            addError(diagnostics_, "E0401",
                     "cannot compare " + left->typeName() + " and " + right->typeName(),
                     expr.location, "both sides must have the same type and unit");
            return std::nullopt;
        }
        bool equal = canonicalText(*left) == canonicalText(*right);
        return makeValue(expr.op == 'e' ? equal : !equal, expr.location);
    }
    if (expr.op == '<' || expr.op == '>' || expr.op == 'l' || expr.op == 'g') {
        const Quantity* a = left->get<Quantity>();
        const Quantity* b = right->get<Quantity>();
        const std::string* sa = left->get<std::string>();
        const std::string* sb = right->get<std::string>();
        int order = 0;
        if (a && b && a->dimension == b->dimension) {
            order = a->value < b->value ? -1 : (a->value > b->value ? 1 : 0);
        } else if (sa && sb) {
            // Strings compare by bytes, which orders canonical dates and times correctly.
            order = sa->compare(*sb) < 0 ? -1 : (sa->compare(*sb) > 0 ? 1 : 0);
        } else {
            addError(diagnostics_, "E0401",
                     "cannot compare " + left->typeName() + " and " + right->typeName(),
                     expr.location, "both sides must be quantities of the same unit");
            return std::nullopt;
        }
        bool result = expr.op == '<'   ? order < 0
                      : expr.op == '>' ? order > 0
                      : expr.op == 'l' ? order <= 0
                                       : order >= 0;
        return makeValue(result, expr.location);
    }
    const char* verb = expr.op == '+'   ? "add"
                       : expr.op == '-' ? "subtract"
                       : expr.op == '*' ? "multiply"
                       : expr.op == '%' ? "take the remainder of"
                                        : "divide";
    const char* joiner = expr.op == '/' ? " by " : " and ";
    const Quantity* a = left->get<Quantity>();
    const Quantity* b = right->get<Quantity>();
    auto incompatible = [&](const std::string& why) -> std::optional<Value> {
        addError(
            diagnostics_, "E0401",
            std::string("cannot ") + verb + " " + left->typeName() + joiner + right->typeName(),
            expr.location, why);
        return std::nullopt;
    };
    if (!a || !b) {
        return incompatible("arithmetic works on numbers and quantities only");
    }
    auto scalar = [](Dimension d) { return d == Dimension::None || d == Dimension::Ratio; };
    Quantity result;
    switch (expr.op) {
        case '+':
        case '-':
            if (a->dimension != b->dimension) {
                return incompatible("the units do not match");
            }
            result = {expr.op == '+' ? a->value + b->value : a->value - b->value, a->dimension};
            break;
        case '*':
            if (!scalar(a->dimension) && !scalar(b->dimension)) {
                return incompatible("only plain numbers and percentages scale a quantity");
            }
            // A percentage scales the other side; a plain number takes the other's unit.
            result = {a->value * b->value, a->dimension == Dimension::Ratio   ? b->dimension
                                           : b->dimension == Dimension::Ratio ? a->dimension
                                           : a->dimension == Dimension::None  ? b->dimension
                                                                              : a->dimension};
            break;
        default:
            if (b->value == 0.0) {
                addError(diagnostics_, "E0408", "division by zero", right->location,
                         "this is zero");
                return std::nullopt;
            }
            if (expr.op == '%') {
                if (a->dimension != b->dimension && !scalar(b->dimension)) {
                    return incompatible("the units do not match");
                }
                result = {std::fmod(a->value, b->value), a->dimension};
            } else if (a->dimension == b->dimension) {
                result = {a->value / b->value, Dimension::None};
            } else if (scalar(b->dimension)) {
                result = {a->value / b->value, a->dimension};
            } else {
                return incompatible("the result would have a unit Sylva does not know");
            }
            break;
    }
    return makeValue(result, expr.location);
}

std::optional<double> Resolver::coerceAngle(const Value& value, const std::string& what) {
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

std::optional<Value> Resolver::evaluateCall(const Expr& expr) {
    static const std::vector<std::string> kFunctions = {"geo",   "min",         "max",  "clamp",
                                                        "interpolate", "step", "match", "distance",
                                                        "destination"};
    if (std::find(kFunctions.begin(), kFunctions.end(), expr.text) == kFunctions.end()) {
        Diagnostic& diagnostic =
            addError(diagnostics_, "E0211", "unknown function '" + expr.text + "'", expr.location,
                     "not a function");
        if (auto match = closestMatch(expr.text, kFunctions)) {
            diagnostic.help.push_back("did you mean '" + *match + "'?");
        }
        diagnostic.help.push_back("functions are: " + join(kFunctions));
        return std::nullopt;
    }
    const std::size_t count = expr.children.size();
    auto arity = [&](bool ok, const std::string& usage) {
        if (!ok) {
            addError(diagnostics_, "E0407",
                     expr.text + "() takes " + usage + ", found " + std::to_string(count),
                     expr.location, "write " + expr.text + "(" + usage + ")");
        }
        return ok;
    };
    bool countOk = true;
    if (expr.text == "geo") {
        if (count < 2 || count > 3) {
            addError(diagnostics_, "E0407",
                     "geo() takes 2 or 3 arguments, found " + std::to_string(count), expr.location,
                     "write geo(latitude, longitude[, height])");
            return std::nullopt;
        }
    } else if (expr.text == "min" || expr.text == "max") {
        countOk = arity(count >= 1, "one or more values");
    } else if (expr.text == "clamp") {
        countOk = arity(count == 3, "value, lowest, highest");
    } else if (expr.text == "interpolate") {
        countOk = arity(count >= 5 && count % 2 == 1, "x, x1, y1, x2, y2, ...");
    } else if (expr.text == "step") {
        countOk = arity(count >= 2 && count % 2 == 0, "x, y0, x1, y1, ...");
    } else if (expr.text == "match") {
        countOk = arity(count >= 4 && count % 2 == 0, "value, key1, result1, ..., default");
    } else if (expr.text == "distance") {
        countOk = arity(count == 2, "from, to");
    } else if (expr.text == "destination") {
        countOk = arity(count == 3, "from, bearing, distance");
    }
    if (!countOk) {
        return std::nullopt;
    }
    std::vector<Value> arguments;
    bool evaluated = true;
    for (const ExprPtr& child : expr.children) {
        std::optional<Value> argument = evaluate(*child, "");
        if (argument) {
            arguments.push_back(std::move(*argument));
        } else {
            evaluated = false;
        }
    }
    if (!evaluated) {
        return std::nullopt;
    }
    if (expr.text == "geo") {
        return evaluateGeo(expr, std::move(arguments));
    }
    if (expr.text == "distance" || expr.text == "destination") {
        // Geodesics on WGS84 (GeographicLib): distance(a, b) in metres;
        // destination(from, bearing, distance) keeps from's height.
        const GeoPosition* from = arguments[0].get<GeoPosition>();
        if (!from) {
            addError(diagnostics_, "E0402", "expected geo position, found " + arguments[0].typeName(),
                     arguments[0].location, expr.text + "() starts at a geo position");
            return std::nullopt;
        }
        Value result;
        result.location = expr.location;
        if (expr.text == "distance") {
            const GeoPosition* to = arguments[1].get<GeoPosition>();
            if (!to) {
                addError(diagnostics_, "E0402", "expected geo position, found " + arguments[1].typeName(),
                         arguments[1].location, "distance() measures between two geo positions");
                return std::nullopt;
            }
            result.data = Quantity{Geodesy::distance(from->latitude, from->longitude, to->latitude, to->longitude),
                                   Dimension::Length};
            return result;
        }
        const Quantity* bearing = arguments[1].get<Quantity>();
        const Quantity* length = arguments[2].get<Quantity>();
        if (!bearing || bearing->dimension != Dimension::Angle) {
            addError(diagnostics_, "E0403", "expected angle, found " + arguments[1].typeName(), arguments[1].location,
                     "the bearing of destination() must be an angle");
            return std::nullopt;
        }
        if (!length || length->dimension != Dimension::Length) {
            addError(diagnostics_, "E0403", "expected length, found " + arguments[2].typeName(), arguments[2].location,
                     "the distance of destination() must be a length");
            return std::nullopt;
        }
        GeoPosition reached = *from;
        Geodesy::destination(from->latitude, from->longitude, bearing->value, length->value, reached.latitude,
                             reached.longitude);
        result.data = reached;
        return result;
    }
    if (expr.text == "match") {
        std::string key = canonicalText(arguments[0]);
        for (std::size_t i = 1; i + 1 < arguments.size(); i += 2) {
            if (canonicalText(arguments[i]) == key) {
                Value result = arguments[i + 1];
                result.location = expr.location;
                return result;
            }
        }
        Value result = arguments.back();
        result.location = expr.location;
        return result;
    }
    // The other functions work on quantities; x and the stops share one unit.
    auto quantityAt = [&](std::size_t i, Dimension dimension) -> const Quantity* {
        const Quantity* quantity = arguments[i].get<Quantity>();
        if (!quantity) {
            addError(diagnostics_, "E0402", "expected a number, found " + arguments[i].typeName(),
                     arguments[i].location, expr.text + "() works on numbers and quantities");
            return nullptr;
        }
        if (quantity->dimension != dimension) {
            addError(diagnostics_, "E0403",
                     std::string("expected ") + dimensionName(dimension) + ", found " +
                         dimensionName(quantity->dimension),
                     arguments[i].location,
                     "the arguments of " + expr.text + "() must share one unit");
            return nullptr;
        }
        return quantity;
    };
    const Quantity* first = arguments[0].get<Quantity>();
    if (!first) {
        quantityAt(0, Dimension::None);
        return std::nullopt;
    }
    if (expr.text == "min" || expr.text == "max" || expr.text == "clamp") {
        Quantity result = *first;
        for (std::size_t i = 1; i < arguments.size(); ++i) {
            const Quantity* other = quantityAt(i, first->dimension);
            if (!other) {
                return std::nullopt;
            }
            if (expr.text == "min" || (expr.text == "clamp" && i == 2)) {
                result.value = std::min(result.value, other->value);
            } else {
                result.value = std::max(result.value, other->value);
            }
        }
        return makeValue(result, expr.location);
    }
    // step / interpolate: stops at odd (interpolate) or odd (step) positions must ascend.
    const bool step = expr.text == "step";
    const std::size_t firstStop = step ? 2 : 1;
    double previous = -HUGE_VAL;
    for (std::size_t i = firstStop; i < arguments.size(); i += 2) {
        const Quantity* stop = quantityAt(i, first->dimension);
        if (!stop) {
            return std::nullopt;
        }
        if (stop->value < previous) {
            addError(diagnostics_, "E0404", "stops of " + expr.text + "() must ascend",
                     arguments[i].location, "smaller than the stop before it");
            return std::nullopt;
        }
        previous = stop->value;
    }
    const double x = first->value;
    if (step) {
        std::size_t chosen = 1;
        for (std::size_t i = 2; i < arguments.size(); i += 2) {
            if (x >= arguments[i].get<Quantity>()->value) {
                chosen = i + 1;
            }
        }
        Value result = arguments[chosen];
        result.location = expr.location;
        return result;
    }
    const Quantity* output = arguments[2].get<Quantity>();
    const Color* colour = arguments[2].get<Color>();
    for (std::size_t i = 2; i < arguments.size(); i += 2) {
        if (output && !quantityAt(i, output->dimension)) {
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
        Value result = arguments[upper == 1 ? 2 : arguments.size() - 1];
        result.location = expr.location;
        return result;
    }
    const double x0 = arguments[upper - 2].get<Quantity>()->value;
    const double x1 = arguments[upper].get<Quantity>()->value;
    const double t = x1 > x0 ? (x - x0) / (x1 - x0) : 1.0;
    const Value& a = arguments[upper - 1];
    const Value& b = arguments[upper + 1];
    if (output) {
        Quantity result{a.get<Quantity>()->value * (1 - t) + b.get<Quantity>()->value * t,
                        output->dimension};
        return makeValue(result, expr.location);
    }
    const Color& ca = *a.get<Color>();
    const Color& cb = *b.get<Color>();
    auto mix = [&](float u, float v) { return static_cast<float>(u * (1 - t) + v * t); };
    return makeValue(Color{mix(ca.r, cb.r), mix(ca.g, cb.g), mix(ca.b, cb.b), mix(ca.a, cb.a)},
                     expr.location);
}

std::optional<Value> Resolver::evaluateGeo(const Expr& expr, std::vector<Value> arguments) {
    std::optional<double> latitude = coerceAngle(arguments[0], "latitude");
    std::optional<double> longitude = coerceAngle(arguments[1], "longitude");
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
        std::optional<Value> height = coerce(arguments[2], heightSchema, "height");
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
    return makeValue(position, expr.location);
}

std::optional<Value> Resolver::coerce(Value value, const AttributeSchema& schema,
                                      const std::string& what) {
    auto wrongType = [&]() -> std::optional<Value> {
        addError(diagnostics_, "E0402",
                 "expected " + expectedName(schema) + ", found " + value.typeName(), value.location,
                 what + " must be " + withArticle(expectedName(schema)));
        return std::nullopt;
    };
    switch (schema.type) {
        case ValueType::Number: {
            Quantity* quantity = std::get_if<Quantity>(&value.data);
            if (!quantity) {
                return wrongType();
            }
            if (quantity->dimension != schema.dimension) {
                if (quantity->dimension != Dimension::None) {
                    addError(diagnostics_, "E0403",
                             std::string("expected ") + dimensionName(schema.dimension) +
                                 ", found " + dimensionName(quantity->dimension),
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
        case ValueType::Bool:
            return value.get<bool>() ? std::optional<Value>(std::move(value)) : wrongType();
        case ValueType::String:
            return value.get<std::string>() ? std::optional<Value>(std::move(value)) : wrongType();
        case ValueType::Color:
            return value.get<Color>() ? std::optional<Value>(std::move(value)) : wrongType();
        case ValueType::Geo: {
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
                return wrongType();
            }
            if (!projectCrs_ && projectCrsInvalid_) {
                return std::nullopt;  // the bad CRS itself is the error
            }
            if (!projectCrs_) {
                Diagnostic& diagnostic =
                    addError(diagnostics_, "E0413", "position in projected coordinates without a project CRS",
                             value.location, what + " is written as [x, y] lengths");
                diagnostic.help.push_back(
                    "declare the CRS, e.g. project { crs = \"EPSG:31985\" }, or write geo(lat, lon)");
                return std::nullopt;
            }
            const std::string& crs = *projectCrs_->get<std::string>();
            Result<GeodeticPoint> point = ProjectedCoordinates::toGeodetic(
                crs, (*list)[0].get<Quantity>()->value, (*list)[1].get<Quantity>()->value);
            if (!point) {
                Diagnostic& diagnostic = addError(diagnostics_, "E0414", point.error().message, value.location,
                                                  "outside what '" + crs + "' can convert");
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
        case ValueType::DateTime: {
            const std::string* text = value.get<std::string>();
            if (!text || !isCanonicalDateTime(*text)) {
                return wrongType();
            }
            return value;
        }
        case ValueType::Object: {
            ValueObject* object = std::get_if<ValueObject>(&value.data);
            if (!object) {
                return wrongType();
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
                    Diagnostic& diagnostic =
                        addError(diagnostics_, "E0208", "unknown key '" + key + "'", item.location,
                                 "not a key of " + what);
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
                bool present = std::any_of(object->begin(), object->end(), [&](const auto& entry) {
                    return entry.first == field.name;
                });
                if (field.required && !present) {
                    addError(diagnostics_, "E0405", "missing required key '" + field.name + "'",
                             value.location, what + " needs '" + field.name + "'")
                        .help.push_back(field.name + ": " + field.doc);
                    ok = false;
                }
            }
            return ok ? std::optional<Value>(std::move(value)) : std::nullopt;
        }
        case ValueType::Word: {
            const Word* word = value.get<Word>();
            if (!word) {
                return wrongType();
            }
            if (!schema.words.empty() && std::find(schema.words.begin(), schema.words.end(),
                                                   word->text) == schema.words.end()) {
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
        case ValueType::Reference: {
            const Reference* reference = value.get<Reference>();
            std::string target = referenceTarget(schema);
            if (!reference) {
                addError(
                    diagnostics_, "E0402",
                    "expected " + expectedName(schema) + " reference, found " + value.typeName(),
                    value.location, what + " must be a reference like '@name'");
                return std::nullopt;
            }
            if (reference->kind != target) {
                addError(diagnostics_, "E0406", "expected " + target + ", found " + reference->kind,
                         value.location,
                         "'" + reference->name + "' is " + withArticle(reference->kind));
                return std::nullopt;
            }
            if (target == "source" && schema.port != PortType::None) {
                const Declaration& declaration = declarations_[names_[reference->name]];
                // A kind whose output depends on its attributes (schema output `none`, e.g.
                // blend, raster, rasterize) is checked by the source graph instead.
                if (declaration.schema && declaration.schema->output != PortType::None &&
                    declaration.schema->output != schema.port) {
                    addError(diagnostics_, "E0406",
                             std::string("expected ") + portTypeName(schema.port) + ", found " +
                                 portTypeName(declaration.schema->output),
                             value.location,
                             "'" + reference->name + "' is " + withArticle(declaration.kind) +
                                 " source, which outputs " +
                                 portTypeName(declaration.schema->output));
                    return std::nullopt;
                }
            }
            return value;
        }
        case ValueType::List: {
            ValueList* list = std::get_if<ValueList>(&value.data);
            if (!list) {
                return wrongType();
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
    }
    return std::nullopt;
}

void Resolver::findCycles(const std::vector<Block>& sources) {
    struct Edge {
        std::string from;
        std::string to;
        SourceLocation location;
    };
    std::map<std::string, std::vector<Edge>> graph;
    std::map<std::string, std::size_t> order;
    for (const Block& source : sources) {
        order.emplace(source.name, order.size());
        std::function<void(const Value&)> collect = [&](const Value& value) {
            if (const Reference* reference = value.get<Reference>()) {
                if (reference->kind == "source") {
                    graph[source.name].push_back({source.name, reference->name, value.location});
                }
            } else if (const ValueList* list = value.get<ValueList>()) {
                for (const Value& item : *list) {
                    collect(item);
                }
            } else if (const ValueObject* object = value.get<ValueObject>()) {
                for (const auto& entry : *object) {
                    collect(entry.second);
                }
            }
        };
        for (const Attribute& attribute : source.attributes) {
            collect(attribute.value);
        }
    }
    std::map<std::string, int> colour;
    std::vector<Edge> path;
    std::set<std::string>& reported = reportedCycles_;
    std::function<void(const std::string&)> visit = [&](const std::string& node) {
        colour[node] = 1;
        for (const Edge& edge : graph[node]) {
            if (colour[edge.to] == 1) {
                // The cycle runs from where the path first left edge.to back to it.
                std::vector<Edge> cycle;
                for (std::size_t i = 0; i < path.size(); ++i) {
                    if (path[i].from == edge.to) {
                        cycle.assign(path.begin() + static_cast<std::ptrdiff_t>(i), path.end());
                        break;
                    }
                }
                cycle.push_back(edge);
                // Start at the source declared first, so the report is stable.
                auto first = std::min_element(
                    cycle.begin(), cycle.end(),
                    [&](const Edge& x, const Edge& y) { return order[x.from] < order[y.from]; });
                std::rotate(cycle.begin(), first, cycle.end());
                std::string chain = cycle.front().from;
                for (const Edge& step : cycle) {
                    chain += " -> " + step.to;
                }
                if (!reported.insert(chain).second) {
                    continue;
                }
                Diagnostic& diagnostic =
                    addError(diagnostics_, "E0301", "dependency cycle between sources",
                             cycle.front().location,
                             "'" + cycle.front().from + "' uses '" + cycle.front().to + "' here");
                for (std::size_t i = 1; i < cycle.size(); ++i) {
                    diagnostic.notes.push_back(
                        {"'" + cycle[i].from + "' uses '" + cycle[i].to + "'", cycle[i].location});
                }
                diagnostic.cycle = chain;
            } else if (colour[edge.to] == 0 && order.count(edge.to)) {
                path.push_back(edge);
                visit(edge.to);
                path.pop_back();
            }
        }
        colour[node] = 2;
    };
    for (const Block& source : sources) {
        if (colour[source.name] == 0) {
            visit(source.name);
        }
    }
}

}  // namespace sylva::dsl
