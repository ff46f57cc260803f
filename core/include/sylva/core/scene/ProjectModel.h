// The evaluated project: plain data produced by the DSL (sylva_dsl) and consumed by
// the source graph, the renderers and the CLI. Blocks keep their attributes as
// checked Values with their source locations, so later stages can still report
// errors at file:line:col. One ProjectModel describes one scenario.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "sylva/core/base/SourceLocation.h"
#include "sylva/core/scene/Value.h"

namespace sylva {

struct Attribute {
    std::string name;
    Value value;
    SourceLocation location;  // of the attribute name
};

struct Block {
    std::string keyword;  // "project", "source", "camera", "views", "render", "scenario", "param" ...
    std::string name;     // empty for anonymous blocks (project, render)
    std::string kind;     // for sources: "noise", "hypsometric" ...; empty otherwise
    SourceLocation location;  // of the block's name (or keyword when anonymous)
    std::vector<Attribute> attributes;

    const Attribute* find(std::string_view attributeName) const {
        for (const Attribute& attribute : attributes) {
            if (attribute.name == attributeName) {
                return &attribute;
            }
        }
        return nullptr;
    }
};

struct ProjectModel {
    std::filesystem::path file;  // the project file as given (absolute or relative to cwd)
    std::string scenario;        // scenario this model describes; empty if the project has none
    Block project;               // keyword "project"; may have no attributes
    Block render;                // keyword "render"; defaults filled in by the DSL from the schema
    std::vector<Block> params;   // keyword "param"; attribute "value" holds the effective value
    std::vector<Block> sources;
    std::vector<Block> scenarios;
    std::vector<Block> cameras;
    std::vector<Block> views;

    const Block* findSource(std::string_view name) const { return findIn(sources, name); }
    const Block* findCamera(std::string_view name) const { return findIn(cameras, name); }
    const Block* findViews(std::string_view name) const { return findIn(views, name); }
    const Block* findScenario(std::string_view name) const { return findIn(scenarios, name); }

private:
    static const Block* findIn(const std::vector<Block>& blocks, std::string_view name) {
        for (const Block& block : blocks) {
            if (block.name == name) {
                return &block;
            }
        }
        return nullptr;
    }
};

}  // namespace sylva
