#include "sylva/dsl/ModelJson.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <nlohmann/json.hpp>

namespace sylva::dsl {

namespace {

using Json = nlohmann::ordered_json;

Json toJson(const Value& value);

struct JsonVisitor {
    Json operator()(std::monostate) const { return nullptr; }
    Json operator()(bool b) const { return b; }
    Json operator()(const Quantity& q) const {
        if (q.dimension == Dimension::None) {
            return q.value;
        }
        return Json{{"value", q.value}, {"dimension", dimensionName(q.dimension)}};
    }
    Json operator()(const std::string& s) const { return s; }
    Json operator()(const Color& c) const {
        auto byte = [](float v) {
            return static_cast<unsigned>(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
        };
        char buffer[16];
        std::snprintf(buffer, sizeof buffer, "#%02x%02x%02x%02x", byte(c.r), byte(c.g), byte(c.b),
                      byte(c.a));
        return Json{{"colour", buffer}};
    }
    Json operator()(const GeoPosition& g) const {
        Json out{{"latitude_rad", g.latitude}, {"longitude_rad", g.longitude}};
        if (g.height) {
            out["height_m"] = *g.height;
        }
        return Json{{"geo", out}};
    }
    Json operator()(const Reference& r) const { return Json{{r.kind, "@" + r.name}}; }
    Json operator()(const Word& w) const { return Json{{"word", w.text}}; }
    Json operator()(const ValueList& list) const {
        Json out = Json::array();
        for (const Value& item : list) {
            out.push_back(toJson(item));
        }
        return out;
    }
    Json operator()(const ValueObject& object) const {
        Json out = Json::object();
        for (const auto& [key, item] : object) {
            out[key] = toJson(item);
        }
        return out;
    }
};

Json toJson(const Value& value) {
    return std::visit(JsonVisitor{}, value.data);
}

Json toJson(const Block& block) {
    Json out;
    out["keyword"] = block.keyword;
    if (!block.name.empty()) {
        out["name"] = block.name;
    }
    if (!block.kind.empty()) {
        out["kind"] = block.kind;
    }
    char hash[24];
    std::snprintf(hash, sizeof hash, "%016llx", static_cast<unsigned long long>(block.contentHash));
    out["hash"] = hash;
    Json attributes = Json::object();
    for (const Attribute& attribute : block.attributes) {
        attributes[attribute.name] = toJson(attribute.value);
    }
    out["attributes"] = attributes;
    return out;
}

Json toJson(const std::vector<Block>& blocks) {
    Json out = Json::array();
    for (const Block& block : blocks) {
        out.push_back(toJson(block));
    }
    return out;
}

}  // namespace

std::string modelsToJson(const std::vector<ProjectModel>& models, int indent) {
    Json scenarios = Json::array();
    for (const ProjectModel& model : models) {
        Json out;
        out["scenario"] = model.scenario;
        out["project"] = toJson(model.project);
        out["render"] = toJson(model.render);
        out["params"] = toJson(model.params);
        out["sources"] = toJson(model.sources);
        out["scenarios"] = toJson(model.scenarios);
        out["cameras"] = toJson(model.cameras);
        out["paths"] = toJson(model.paths);
        out["views"] = toJson(model.views);
        out["compares"] = toJson(model.compares);
        out["blends"] = toJson(model.blends);
        if (!model.ztvs.empty())
            out["ztvs"] = toJson(model.ztvs);
        if (!model.shadowStudies.empty())
            out["shadow_studies"] = toJson(model.shadowStudies);
        if (!model.photos.empty())
            out["photos"] = toJson(model.photos);
        scenarios.push_back(std::move(out));
    }
    Json root;
    root["scenarios"] = std::move(scenarios);
    return root.dump(indent) + "\n";
}

}  // namespace sylva::dsl
