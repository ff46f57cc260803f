#include "sylva/dsl/ModelHash.h"

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <functional>
#include <string_view>
#include <system_error>
#include <unordered_map>
#include <vector>

namespace sylva::dsl {

namespace {

// Shortest text that reads back to the same double (std::to_chars is exact and fast).
std::string number(double value) {
    char buffer[40];
    auto [end, error] = std::to_chars(buffer, buffer + sizeof buffer, value);
    return error == std::errc() ? std::string(buffer, end) : std::string("nan");
}

std::string quoted(const std::string& text) {
    std::string out = "\"";
    for (char c : text) {
        if (c == '"' || c == '\\') {
            out += '\\';
        }
        out += c;
    }
    return out + "\"";
}

struct CanonicalVisitor {
    std::string operator()(std::monostate) const { return "null"; }
    std::string operator()(bool b) const { return b ? "true" : "false"; }
    std::string operator()(const Quantity& q) const {
        return "q(" + number(q.value) + "," + dimensionName(q.dimension) + ")";
    }
    std::string operator()(const std::string& s) const { return quoted(s); }
    std::string operator()(const Color& c) const {
        return "rgba(" + number(c.r) + "," + number(c.g) + "," + number(c.b) + "," + number(c.a) +
               ")";
    }
    std::string operator()(const GeoPosition& g) const {
        std::string out = "geo(";
        out += number(g.latitude);
        out += ",";
        out += number(g.longitude);
        if (g.height) {
            out += ",";
            out += number(*g.height);
        }
        out += ")";
        return out;
    }
    std::string operator()(const Reference& r) const { return "@" + r.kind + ":" + r.name; }
    std::string operator()(const Word& w) const { return "w:" + w.text; }
    std::string operator()(const ValueList& list) const {
        std::string out = "[";
        for (const Value& item : list) {
            out += canonicalText(item) + ",";
        }
        return out + "]";
    }
    std::string operator()(const ValueObject& object) const {
        std::string out = "{";
        for (const auto& [key, item] : object) {
            out += quoted(key) + "=" + canonicalText(item) + ",";
        }
        return out + "}";
    }
};

void collectReferences(const Value& value, std::vector<std::string>& names) {
    if (const Reference* reference = value.get<Reference>()) {
        if (reference->kind == "source") {
            names.push_back(reference->name);
        }
    } else if (const ValueList* list = value.get<ValueList>()) {
        for (const Value& item : *list) {
            collectReferences(item, names);
        }
    } else if (const ValueObject* object = value.get<ValueObject>()) {
        for (const auto& entry : *object) {
            collectReferences(entry.second, names);
        }
    }
}

std::string ownText(const Block& block) {
    std::vector<const Attribute*> sorted;
    for (const Attribute& attribute : block.attributes) {
        sorted.push_back(&attribute);
    }
    std::sort(sorted.begin(), sorted.end(),
              [](const Attribute* a, const Attribute* b) { return a->name < b->name; });
    std::string text = block.keyword + ":" + block.kind + "{";
    for (const Attribute* attribute : sorted) {
        text += attribute->name + "=" + canonicalText(attribute->value) + ";";
    }
    return text + "}";
}

}  // namespace

std::string canonicalText(const Value& value) {
    return std::visit(CanonicalVisitor{}, value.data);
}

std::uint64_t fnv1a(const std::string& text) {
    std::uint64_t hash = 14695981039346656037ull;
    for (unsigned char c : text) {
        hash ^= c;
        hash *= 1099511628211ull;
    }
    return hash;
}

void computeContentHashes(ProjectModel& model, const std::vector<std::string>* changed) {
    std::unordered_map<std::string_view, std::size_t> sources;
    for (std::size_t i = 0; i < model.sources.size(); ++i) {
        sources.emplace(model.sources[i].name, i);
    }
    // 1 visiting, 2 done: a cycle (already reported as an error) stops the recursion.
    std::vector<int> state(model.sources.size(), 0);
    if (changed) {
        // Keep every hash except those of changed sources and of their dependants.
        std::vector<std::vector<std::size_t>> dependants(model.sources.size());
        for (std::size_t i = 0; i < model.sources.size(); ++i) {
            std::vector<std::string> names;
            for (const Attribute& attribute : model.sources[i].attributes) {
                collectReferences(attribute.value, names);
            }
            for (const std::string& name : names) {
                if (auto found = sources.find(name); found != sources.end()) {
                    dependants[found->second].push_back(i);
                }
            }
        }
        std::vector<char> dirty(model.sources.size(), 0);
        std::vector<std::size_t> work;
        for (const std::string& name : *changed) {
            if (auto found = sources.find(name); found != sources.end()) {
                work.push_back(found->second);
            }
        }
        while (!work.empty()) {
            std::size_t index = work.back();
            work.pop_back();
            if (dirty[index]) {
                continue;
            }
            dirty[index] = 1;
            work.insert(work.end(), dependants[index].begin(), dependants[index].end());
        }
        for (std::size_t i = 0; i < state.size(); ++i) {
            state[i] = dirty[i] ? 0 : 2;
        }
    }
    std::function<std::uint64_t(std::size_t)> hashSource = [&](std::size_t index) -> std::uint64_t {
        Block& block = model.sources[index];
        if (state[index] == 2) {
            return block.contentHash;
        }
        if (state[index] == 1) {
            return 0;
        }
        state[index] = 1;
        std::string text = ownText(block);
        std::vector<std::string> names;
        for (const Attribute& attribute : block.attributes) {
            collectReferences(attribute.value, names);
        }
        for (const std::string& name : names) {
            auto found = sources.find(name);
            if (found != sources.end()) {
                text += "|";
                text += name;
                text += "#";
                text += std::to_string(hashSource(found->second));
            }
        }
        block.contentHash = fnv1a(text);
        state[index] = 2;
        return block.contentHash;
    };
    for (std::size_t i = 0; i < model.sources.size(); ++i) {
        hashSource(i);
    }
    for (std::vector<Block>* blocks :
         {&model.scenarios, &model.cameras, &model.views, &model.compares, &model.blends,
          &model.paths, &model.params, &model.ztvs, &model.shadowStudies, &model.photos}) {
        for (Block& block : *blocks) {
            block.contentHash = fnv1a(block.name + "|" + ownText(block));
        }
    }
    model.project.contentHash = fnv1a(ownText(model.project));
    model.render.contentHash = fnv1a(ownText(model.render));
}

}  // namespace sylva::dsl
