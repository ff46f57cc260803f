// The Resolver runs the checks in order: names (NameScope), -D and --set, params
// (ExpressionEvaluator), blocks with the project block first (BlockChecker), scenarios
// with their `extends` and overrides, then one model per scenario with its content
// hashes and graph checks (GraphChecker).
#include "sylva/dsl/Resolver.h"

#include <algorithm>
#include <set>
#include <string>
#include <utility>

#include "BlockChecker.h"
#include "DiagnosticText.h"
#include "ExpressionEvaluator.h"
#include "GraphChecker.h"
#include "MakeValue.h"
#include "NameScope.h"
#include "PlantSeasonChecker.h"
#include "ValueChecker.h"
#include "sylva/core/geo/ProjectedCoordinates.h"
#include "sylva/dsl/EditDistance.h"
#include "sylva/dsl/ModelHash.h"

namespace sylva::dsl {

namespace {
// The override target key of `override render { ... }` (no block name can contain '#').
constexpr const char* kRenderOverride = "#render";
}  // namespace

Resolver::Resolver(const SchemaRegistry& schema, std::vector<Diagnostic>& diagnostics)
    : schema_(schema), diagnostics_(diagnostics) {}

Resolver::~Resolver() = default;

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
    // Every call starts afresh.
    setPatches_.clear();
    implicit_.clear();
    names_ = std::make_unique<NameScope>(schema_, diagnostics_);
    values_ = std::make_unique<ValueChecker>(*names_, diagnostics_);
    expressions_ =
        std::make_unique<ExpressionEvaluator>(*names_, *values_, setPatches_, diagnostics_);
    blocks_ = std::make_unique<BlockChecker>(*expressions_, *values_, diagnostics_, options.lenient,
                                             path.parent_path());
    graph_ = std::make_unique<GraphChecker>(schema_, diagnostics_);

    names_->declareAll(units);
    names_->applyDefines(defines);
    collectSets(sets);
    evaluateParams();
    addImplicitBlocks();
    ProjectModel model = checkBlocks(path);
    const std::vector<Declaration*> scenarios = resolveScenarios(model);
    addOmittedBlocks(model, path);
    collectParams(model);
    std::vector<ProjectModel> models = scenarioModels(std::move(model), scenarios);
    if (!scenarios.empty()) {
        reportUnusedSources(models);
    }
    if (hasErrors(diagnostics_)) {
        return {};
    }
    return models;
}

// --set names a block (E0213 otherwise); its attribute replaces the block's own.
void Resolver::collectSets(const std::vector<SetNode>& sets) {
    for (const SetNode& set : sets) {
        const Declaration* found = names_->find(set.block);
        bool known = set.block == "project" || set.block == "render" || (found && found->block);
        if (known) {
            setPatches_[set.block].push_back({&set.attribute, ""});
            continue;
        }
        std::vector<std::string> blocks = {"project", "render"};
        for (const Declaration& declaration : names_->declarations()) {
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
    }
}

// Every param once, in declaration order, so unused ones are checked too.
void Resolver::evaluateParams() {
    for (Declaration& declaration : names_->declarations()) {
        if (declaration.keyword == "param") {
            expressions_->evaluateParam(declaration, declaration.location);
        }
    }
}

// --set on a project/render block the files omit still has to be checked.
void Resolver::addImplicitBlocks() {
    for (const char* keyword : {"project", "render"}) {
        const BlockNode* written =
            std::string_view(keyword) == "project" ? names_->project() : names_->render();
        const KindSchema* kindSchema = schema_.find(keyword);
        if (!written && kindSchema && setPatches_.count(keyword)) {
            auto node = std::make_unique<BlockNode>();
            node->keyword = keyword;
            node->keywordLocation = setPatches_[keyword].front().attribute->nameLocation;
            names_->blocks().push_back({node.get(), kindSchema, ""});
            implicit_.push_back(std::move(node));
        }
    }
}

// Every block but the scenarios (which inherit from each other, see resolveScenarios),
// the project block first: its `crs` is needed to read positions written in projected
// coordinates anywhere else.
ProjectModel Resolver::checkBlocks(const std::filesystem::path& path) {
    ProjectModel model;
    model.file = path;
    std::vector<const BlockEntry*> ordered;
    for (const BlockEntry& entry : names_->blocks()) {
        if (entry.node->keyword == "project") {
            ordered.push_back(&entry);
        }
    }
    for (const BlockEntry& entry : names_->blocks()) {
        if (entry.node->keyword != "project") {
            ordered.push_back(&entry);
        }
    }
    for (const BlockEntry* entry : ordered) {
        if (entry->node->keyword == "scenario") {
            continue;
        }
        const std::string& key =
            entry->node->name.empty() ? entry->node->keyword : entry->scope + entry->node->name;
        addToModel(model, blocks_->check(*entry, setPatchesOf(key)));
    }
    return model;
}

void Resolver::addToModel(ProjectModel& model, Block block) {
    const std::string keyword = block.keyword;
    if (keyword == "source") {
        checkPlantSeasons(block, diagnostics_);
        model.sources.push_back(std::move(block));
    } else if (keyword == "camera") {
        model.cameras.push_back(std::move(block));
    } else if (keyword == "views") {
        model.views.push_back(std::move(block));
    } else if (keyword == "compare") {
        model.compares.push_back(std::move(block));
    } else if (keyword == "blend") {
        model.blends.push_back(std::move(block));
    } else if (keyword == "path") {
        model.paths.push_back(std::move(block));
    } else if (keyword == "ztv") {
        model.ztvs.push_back(std::move(block));
    } else if (keyword == "shadow_study") {
        model.shadowStudies.push_back(std::move(block));
    } else if (keyword == "photo") {
        model.photos.push_back(std::move(block));
    } else if (keyword == "project") {
        model.project = std::move(block);
        acceptProjectCrs(model.project);
    } else if (keyword == "render") {
        model.render = std::move(block);
    }
}

// The project's crs, checked once here, is what [x, y] positions are read in.
void Resolver::acceptProjectCrs(const Block& project) {
    const Attribute* crs = project.find("crs");
    const std::string* text = crs ? crs->value.get<std::string>() : nullptr;
    if (text == nullptr || text->empty()) {
        return;
    }
    if (Status valid = ProjectedCoordinates::validate(*text); !valid) {
        values_->setProjectCrsInvalid();  // reported once, here
        addError(diagnostics_, "E0414", valid.error().message, crs->value.location,
                 "not a coordinate reference system GDAL/PROJ can convert to WGS84");
    } else {
        values_->setProjectCrs(crs->value);
    }
}

// The scenarios that resolve, in declaration order; their blocks go into the model.
std::vector<Declaration*> Resolver::resolveScenarios(ProjectModel& model) {
    std::vector<Declaration*> scenarios;
    for (Declaration& declaration : names_->declarations()) {
        if (declaration.keyword == "scenario" && declaration.schema) {
            resolveScenario(declaration);
            if (declaration.scenarioBlock) {
                model.scenarios.push_back(*declaration.scenarioBlock);
                scenarios.push_back(&declaration);
            }
        }
    }
    return scenarios;
}

void Resolver::resolveScenario(Declaration& scenario) {
    if (scenario.scenarioState == EvaluationState::Done) {
        return;
    }
    scenario.scenarioState = EvaluationState::Evaluating;
    const Block* inherited = nullptr;
    if (!resolveParent(scenario, inherited)) {
        scenario.scenarioState = EvaluationState::Done;
        return;  // the parent has errors; do not pile more on
    }
    BlockEntry entry{scenario.block, scenario.schema, scenario.scope};
    scenario.scenarioBlock = blocks_->check(entry, setPatchesOf(scenario.name), inherited);
    collectOverrides(scenario);
    scenario.scenarioState = EvaluationState::Done;
}

bool Resolver::resolveParent(Declaration& scenario, const Block*& inherited) {
    const BlockNode& node = *scenario.block;
    if (node.extends.empty()) {
        return true;
    }
    std::vector<std::string> fields;
    Declaration* parent = names_->lookup(scenario.scope, node.extends, &fields);
    if (!parent || !fields.empty()) {
        Diagnostic& diagnostic =
            addError(diagnostics_, "E0201", "unknown scenario '" + node.extends + "'",
                     node.extendsLocation, "no scenario named '" + node.extends + "'");
        if (auto match = closestMatch(node.extends, names_->namesOf({"scenario"}))) {
            diagnostic.help.push_back("did you mean '" + *match + "'?");
        }
    } else if (parent->keyword != "scenario") {
        addError(diagnostics_, "E0406", "expected scenario, found " + parent->keyword,
                 node.extendsLocation, "'" + parent->name + "' is " + withArticle(parent->keyword));
    } else if (parent->scenarioState == EvaluationState::Evaluating) {
        bool self = parent == &scenario;
        addError(
            diagnostics_, "E0303",
            self ? "scenario '" + scenario.name + "' extends itself"
                 : "scenarios '" + scenario.name + "' and '" + parent->name + "' extend each other",
            node.extendsLocation, "'" + scenario.name + "' extends '" + parent->name + "' here")
            .help.push_back("a scenario cannot inherit from itself, directly or through others");
    } else {
        resolveScenario(*parent);
        if (!parent->scenarioBlock) {
            return false;
        }
        inherited = &*parent->scenarioBlock;
        scenario.overrideAttributes = parent->overrideAttributes;
        scenario.overrideScopes = parent->overrideScopes;
    }
    return true;
}

// `override @target { ... }`: only sources and cameras, appended to the inherited ones;
// `override render { ... }`: the render block of this scenario (kRenderOverride).
void Resolver::collectOverrides(Declaration& scenario) {
    for (const OverrideNode& override : scenario.block->overrides) {
        if (override.render) {
            for (const AttributeNode& attribute : override.attributes) {
                scenario.overrideAttributes.emplace_back(kRenderOverride, &attribute);
                scenario.overrideScopes.push_back(scenario.scope);
            }
            continue;
        }
        std::vector<std::string> fields;
        Declaration* target = names_->lookup(scenario.scope, override.target, &fields);
        if (!target || !fields.empty()) {
            Diagnostic& diagnostic =
                addError(diagnostics_, "E0201", "unknown reference '@" + override.target + "'",
                         override.targetLocation, "no source named '" + override.target + "'");
            if (auto match = closestMatch(override.target, names_->namesOf({"source", "camera"}))) {
                diagnostic.help.push_back(names_->suggestion("@" + *match, *match));
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
}

// project and render exist even when the files omit them.
void Resolver::addOmittedBlocks(ProjectModel& model, const std::filesystem::path& path) {
    for (Block* block : {&model.project, &model.render}) {
        if (block->keyword.empty()) {
            block->keyword = block == &model.project ? "project" : "render";
            block->location.file = std::make_shared<const std::string>(path.string());
            if (const KindSchema* kindSchema = schema_.find(block->keyword)) {
                BlockChecker::fillDefaults(*block, *kindSchema);
            }
        }
    }
}

// The effective params (W0201 for unused ones) as `param` blocks of the model.
void Resolver::collectParams(ProjectModel& model) {
    for (const Declaration& declaration : names_->declarations()) {
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
}

namespace {

// Adds the names of the sources `value` refers to (through lists and objects) to `used`.
void collectSourceReferences(const Value& value, std::set<std::string>& used) {
    if (const Reference* reference = value.get<Reference>()) {
        if (reference->kind == "source") {
            used.insert(reference->name);
        }
    } else if (const ValueList* list = value.get<ValueList>()) {
        for (const Value& element : *list) {
            collectSourceReferences(element, used);
        }
    } else if (const ValueObject* object = value.get<ValueObject>()) {
        for (const auto& [field, element] : *object) {
            collectSourceReferences(element, used);
        }
    }
}

}  // namespace

// W0203 for a source of the project file itself (imported libraries may offer more than a
// project takes) that no block of any scenario model refers to: not a scenario's layers,
// not a view, analysis block or other source (a source naming only itself does not count).
// Reported only when the project has scenarios: without one nothing is drawn at all.
void Resolver::reportUnusedSources(const std::vector<ProjectModel>& models) {
    std::set<std::string> used;
    for (const ProjectModel& model : models) {
        for (const std::vector<Block>* blocks :
             {&model.sources, &model.scenarios, &model.cameras, &model.views, &model.compares,
              &model.blends, &model.paths, &model.ztvs, &model.shadowStudies, &model.photos}) {
            for (const Block& block : *blocks) {
                std::set<std::string> referenced;
                for (const Attribute& attribute : block.attributes) {
                    collectSourceReferences(attribute.value, referenced);
                }
                if (block.keyword == "source") {
                    referenced.erase(block.name);
                }
                used.insert(referenced.begin(), referenced.end());
            }
        }
    }
    for (const Declaration& declaration : names_->declarations()) {
        if (declaration.keyword == "source" && declaration.schema != nullptr &&
            declaration.scope.empty() && !used.count(declaration.name)) {
            addWarning(diagnostics_, "W0203", "unused source '" + declaration.name + "'",
                       declaration.location,
                       "no scenario, view, analysis or other source refers to it");
        }
    }
}

// The base model, or one copy per scenario with its overrides applied; only the changed
// sources and their dependants are rehashed, and an unchanged graph is checked once.
std::vector<ProjectModel> Resolver::scenarioModels(ProjectModel model,
                                                   const std::vector<Declaration*>& scenarios) {
    std::vector<ProjectModel> models;
    computeContentHashes(model);
    if (scenarios.empty()) {
        graph_->findCycles(model.sources);
        graph_->checkPortTypes(model.sources);
        models.push_back(std::move(model));
    }
    for (const Declaration* scenario : scenarios) {
        ProjectModel scenarioModel = model;
        scenarioModel.scenario = scenario->name;
        std::vector<std::string> changed = applyOverrides(scenarioModel, *scenario);
        if (!changed.empty() || scenario == scenarios.front()) {
            graph_->findCycles(scenarioModel.sources);
            graph_->checkPortTypes(scenarioModel.sources);
        }
        computeContentHashes(scenarioModel, &changed);
        models.push_back(std::move(scenarioModel));
    }
    return models;
}

std::vector<std::string> Resolver::applyOverrides(ProjectModel& model,
                                                  const Declaration& scenario) {
    // The overrides of this scenario (inherited ones first), by target block.
    std::map<std::string, std::vector<Patch>> overrides;
    for (std::size_t i = 0; i < scenario.overrideAttributes.size(); ++i) {
        const auto& [target, attribute] = scenario.overrideAttributes[i];
        overrides[target].push_back({attribute, scenario.overrideScopes[i]});
    }
    std::vector<std::string> changed;
    for (const auto& [target, patches] : overrides) {
        if (target == kRenderOverride) {
            model.render = renderBlockWith(patches);
            continue;  // not a source: nothing to rehash but the render block itself
        }
        changed.push_back(target);
        const Declaration& declaration = *names_->find(target);
        std::vector<Block>& blocks =
            declaration.keyword == "source" ? model.sources : model.cameras;
        auto found = std::find_if(blocks.begin(), blocks.end(),
                                  [&](const Block& block) { return block.name == target; });
        if (found == blocks.end()) {
            continue;  // the block itself has errors, already reported
        }
        std::vector<Patch> all = setPatchesOf(target);
        all.insert(all.end(), patches.begin(), patches.end());
        BlockEntry entry{declaration.block, declaration.schema, declaration.scope};
        *found = blocks_->check(entry, all);
    }
    return changed;
}

// The render block checked again with `patches` after its --set patches (an empty block
// with the schema's defaults when the files have none).
Block Resolver::renderBlockWith(const std::vector<Patch>& patches) {
    const BlockNode* node = names_->render();
    if (node == nullptr) {
        for (const BlockEntry& entry : names_->blocks()) {
            if (entry.node->keyword == "render") {
                node = entry.node;  // the implicit block of --set render.…
            }
        }
    }
    if (node == nullptr) {
        auto implicit = std::make_unique<BlockNode>();
        implicit->keyword = "render";
        implicit->keywordLocation = patches.front().attribute->nameLocation;
        node = implicit.get();
        implicit_.push_back(std::move(implicit));
    }
    std::vector<Patch> all = setPatchesOf("render");
    all.insert(all.end(), patches.begin(), patches.end());
    return blocks_->check(BlockEntry{node, schema_.find("render"), ""}, all);
}

const std::vector<Patch>& Resolver::setPatchesOf(const std::string& block) const {
    static const std::vector<Patch> kNone;
    auto found = setPatches_.find(block);
    return found == setPatches_.end() ? kNone : found->second;
}

}  // namespace sylva::dsl
