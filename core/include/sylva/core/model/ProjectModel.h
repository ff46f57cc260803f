// The evaluated project: plain data produced by the DSL (sylva_dsl) and consumed by
// the source graph, the renderers and the CLI. Blocks keep their attributes as
// checked Values with their source locations, so later stages can still report
// errors at file:line:col. One ProjectModel describes one scenario.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "sylva/core/base/SourceLocation.h"
#include "sylva/core/model/Value.h"

namespace sylva {

struct Attribute {
    std::string name;
    Value value;
    SourceLocation location;  // of the attribute name
};

struct Block {
    std::string
        keyword;       // "project", "source", "camera", "views", "render", "scenario", "param" ...
    std::string name;  // empty for anonymous blocks (project, render)
    std::string kind;  // for sources: "noise", "hypsometric" ...; empty otherwise
    SourceLocation location;  // of the block's name (or keyword when anonymous)
    std::vector<Attribute> attributes;
    // Hash of kind, attributes and the hashes of referenced sources: blocks with equal
    // hashes compute equal data, so scenarios share them. 0 when not computed.
    std::uint64_t contentHash = 0;

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
    std::vector<Block> compares;       // keyword "compare": two scenarios side by side
    std::vector<Block> blends;         // keyword "blend": a mix of two scenarios
    std::vector<Block> paths;          // keyword "path": camera animations
    std::vector<Block> ztvs;           // keyword "ztv": zones of theoretical visibility (analyse)
    std::vector<Block> shadowStudies;  // keyword "shadow_study": sun and shadow (analyse)
    std::vector<Block> photos;         // keyword "photo": photomontages (montage)

    const Block* findSource(std::string_view name) const { return findIn(sources, name); }
    const Block* findCamera(std::string_view name) const { return findIn(cameras, name); }
    const Block* findViews(std::string_view name) const { return findIn(views, name); }
    const Block* findScenario(std::string_view name) const { return findIn(scenarios, name); }
    const Block* findPath(std::string_view name) const { return findIn(paths, name); }

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
