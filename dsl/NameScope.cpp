#include "NameScope.h"

#include <algorithm>

#include "DiagnosticText.h"
#include "sylva/core/base/Check.h"
#include "sylva/dsl/EditDistance.h"

namespace sylva::dsl {

namespace {

bool isAnonymousKeyword(const std::string& keyword) {
    return keyword == "project" || keyword == "render";
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

}  // namespace

NameScope::NameScope(const SchemaRegistry& schema, std::vector<Diagnostic>& diagnostics)
    : schema_(schema), diagnostics_(diagnostics) {
    for (const KindSchema& kindSchema : schema_.all()) {
        if (std::find(keywords_.begin(), keywords_.end(), kindSchema.keyword) == keywords_.end()) {
            keywords_.push_back(kindSchema.keyword);
        }
    }
}

void NameScope::declareAll(const std::vector<ParsedUnit>& units) {
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
}

void NameScope::applyDefines(const std::vector<DefineNode>& defines) {
    for (const DefineNode& define : defines) {
        Declaration* param = find(define.name);
        if (!param || param->keyword != "param") {
            Diagnostic& diagnostic =
                addError(diagnostics_, "E0207", "undeclared param '" + define.name + "'",
                         define.nameLocation, "no param named '" + define.name + "'");
            if (auto match = closestMatch(define.name, namesOf({"param"}))) {
                diagnostic.help.push_back(suggestion(*match, *match));
            }
            diagnostic.help.push_back("-D sets only params declared with 'param'");
            continue;
        }
        if (define.value) {
            param->valueExpr = define.value.get();
            param->valueScope = "";
        } else {
            // The value did not parse (already reported); keep the param quiet.
            param->valueExpr = nullptr;
            param->state = EvaluationState::Done;
        }
    }
}

Declaration* NameScope::lookup(const std::string& scope, const std::string& written,
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

Declaration* NameScope::find(std::string_view name) {
    auto found = names_.find(name);
    return found == names_.end() ? nullptr : &declarations_[found->second];
}

const Declaration* NameScope::find(std::string_view name) const {
    auto found = names_.find(name);
    return found == names_.end() ? nullptr : &declarations_[found->second];
}

std::vector<std::string> NameScope::namesOf(
    std::initializer_list<std::string_view> keywords) const {
    std::vector<std::string> names;
    for (const Declaration& declaration : declarations_) {
        if (std::find(keywords.begin(), keywords.end(), declaration.keyword) != keywords.end()) {
            names.push_back(declaration.name);
        }
    }
    return names;
}

std::string NameScope::suggestion(const std::string& shown, const std::string& name) const {
    const Declaration* declaration = find(name);
    SYLVA_CHECK(declaration != nullptr);  // suggestions are made from declared names
    return "did you mean '" + shown + "' (defined at " + shortLocation(declaration->location) +
           ")?";
}

void NameScope::declare(const Statement& statement, const std::string& scope) {
    if (std::holds_alternative<ImportNode>(statement)) {
        return;  // the loader follows imports; their files arrive as units of their own
    }
    if (const auto* param = std::get_if<ParamNode>(&statement)) {
        declareParam(*param, scope);
        return;
    }
    declareBlock(std::get<BlockNode>(statement), scope);
}

void NameScope::declareParam(const ParamNode& param, const std::string& scope) {
    Declaration declaration;
    declaration.keyword = "param";
    declaration.name = scope + param.name;
    declaration.scope = scope;
    declaration.valueScope = scope;
    declaration.location = param.nameLocation;
    declaration.param = &param;
    declaration.valueExpr = param.defaultValue.get();
    add(std::move(declaration));
}

void NameScope::declareBlock(const BlockNode& block, const std::string& scope) {
    if (!isKeyword(block)) {
        return;
    }
    checkScenarioSyntax(block);
    const std::string& keyword = block.keyword;
    const KindSchema* kindSchema = nullptr;
    if (keyword == "source") {
        if (!sourceSchema(block, kindSchema)) {
            return;
        }
    } else {
        kindSchema = schema_.find(keyword);
        if (!block.kind.empty()) {
            addError(diagnostics_, "E0205", "'" + keyword + "' blocks have no kind",
                     block.kindLocation, "only sources have a kind");
            return;
        }
        if (isAnonymousKeyword(keyword)) {
            declareAnonymous(block, kindSchema, scope);
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
    if (add(std::move(declaration)) && kindSchema) {
        blocks_.push_back({&block, kindSchema, scope});
    }
}

bool NameScope::isKeyword(const BlockNode& block) {
    if (std::find(keywords_.begin(), keywords_.end(), block.keyword) != keywords_.end()) {
        return true;
    }
    Diagnostic& diagnostic =
        addError(diagnostics_, "E0203", "unknown block keyword '" + block.keyword + "'",
                 block.keywordLocation, "not a block keyword");
    if (auto match = closestMatch(block.keyword, keywords_)) {
        diagnostic.help.push_back("did you mean '" + *match + "'?");
    }
    diagnostic.help.push_back("block keywords are: param, " + join(keywords_));
    return false;
}

void NameScope::checkScenarioSyntax(const BlockNode& block) {
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
}

bool NameScope::sourceSchema(const BlockNode& block, const KindSchema*& kindSchema) {
    if (block.name.empty()) {
        addError(diagnostics_, "E0205", "source needs a name and a kind", block.keywordLocation,
                 "write 'source NAME : KIND { ... }'");
        return false;
    }
    if (block.kind.empty()) {
        addError(diagnostics_, "E0205", "source '" + block.name + "' needs a kind",
                 block.nameLocation, "write 'source " + block.name + " : KIND { ... }'");
        return true;  // declared all the same, so references to it do not pile up errors
    }
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
    return true;
}

void NameScope::declareAnonymous(const BlockNode& block, const KindSchema* kindSchema,
                                 const std::string& scope) {
    const std::string& keyword = block.keyword;
    if (!block.name.empty()) {
        addError(diagnostics_, "E0205", "'" + keyword + "' block takes no name", block.nameLocation,
                 "remove this name");
        return;
    }
    const BlockNode*& first = keyword == "project" ? project_ : render_;
    if (first) {
        addError(diagnostics_, "E0206", "duplicate '" + keyword + "' block", block.keywordLocation,
                 "second '" + keyword + "' block")
            .notes.push_back({"first '" + keyword + "' block here", first->keywordLocation});
        return;
    }
    first = &block;
    blocks_.push_back({&block, kindSchema, scope});
}

bool NameScope::add(Declaration declaration) {
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

}  // namespace sylva::dsl
