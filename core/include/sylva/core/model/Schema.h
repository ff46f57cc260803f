// The schema registry: every block keyword and source kind Sylva understands, with
// its attributes (type or typed port, unit dimension, default, range, required flag,
// documentation). Filled by sylva_core (schema/BuiltinSchema.cpp); the DSL checks
// projects against it, `sylva doc` prints it, docs/dsl.md is generated from it.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "sylva/core/model/Value.h"

namespace sylva {

// What flows along an edge of the source graph.
enum class PortType {
    None,
    Elevation,   // metres above the WGS84 ellipsoid, one channel
    Image,       // colour, linear RGB(A)
    Normals,     // unit surface normals in ECEF, three channels
    Mask,        // one channel in [0, 1]
    Features,    // vector features (points, lines, polygons)
    Instances,   // plant instances
    PlantModel,  // one plant species: source mesh and LoD (PlantModelSource)
    Meshes,      // 3D geometry on the terrain: buildings, placed models (MeshSource)
};

const char* portTypeName(PortType type);  // "elevation", "image", ..., "plant_model"

enum class ValueType {
    Number,  // a Quantity; `dimension` says which
    Bool,
    String,
    Color,
    Geo,        // geo(lat, lon[, height])
    Word,       // one of `words`
    Reference,  // @name of a block; `port` (sources) or `target` (other blocks) says which
    List,       // of `element`
    Object,     // { key = value }: free keys, or the keys listed in `fields`
    DateTime,   // an ISO date-time or time literal (2024-06-21T14:30+02:00, 14:30)
};

struct AttributeSchema {
    std::string name;
    ValueType type = ValueType::Number;
    Dimension dimension = Dimension::None;  // for Number (and List of Number)
    PortType port = PortType::None;         // for Reference to a source
    std::string target;  // for Reference to a non-source block: "camera", "scenario"
    ValueType element = ValueType::Number;  // for List
    std::vector<std::string> words;         // for Word
    std::optional<double> minimum;          // inclusive, in SI units
    std::optional<double> maximum;          // inclusive, in SI units
    std::optional<Value> defaultValue;      // absent: no default
    bool required = false;
    std::string doc;
    // For Object (and List of Object): the keys a record may hold. Empty: free keys.
    std::vector<AttributeSchema> fields;
};

struct KindSchema {
    std::string keyword;               // "source", "camera", "render" ...
    std::string kind;                  // source kind ("noise"); empty for other blocks
    PortType output = PortType::None;  // for sources
    std::string doc;
    std::vector<AttributeSchema> attributes;

    const AttributeSchema* find(std::string_view name) const;
};

class SchemaRegistry {
public:
    // The registry of everything built into this Sylva.
    static const SchemaRegistry& builtin();

    void add(KindSchema kind);
    // Lookup by block keyword and, for sources, kind; nullptr if unknown.
    const KindSchema* find(std::string_view keyword, std::string_view kind = {}) const;
    // Source kinds in registration order, for did-you-mean and `sylva doc`.
    std::vector<std::string> sourceKinds() const;
    const std::vector<KindSchema>& all() const { return kinds_; }
    // Mutable lookup, so later registration steps can extend a kind; nullptr if unknown.
    KindSchema* edit(std::string_view keyword, std::string_view kind = {}) {
        return const_cast<KindSchema*>(find(keyword, kind));
    }

    // For source kinds whose output depends on the block (output == None): the attribute
    // that decides it, either a word attribute whose value names a port type
    // ("elevation", "image"; other words leave it open until the graph is built) or a
    // port attribute whose source's output is passed on. Empty: decided at graph build.
    void setOutputFrom(std::string_view kind, std::string attribute);
    std::string_view outputFrom(std::string_view kind) const;

private:
    std::vector<KindSchema> kinds_;
    std::vector<std::pair<std::string, std::string>> outputFrom_;  // kind, attribute
};

// Registers the blocks of the project language that are not sources (compare, blend,
// path) and extends views/scenario with their language-level attributes. Called at the
// end of the builtin registry's construction (schema/LanguageSchema.cpp).
void addLanguageSchema(SchemaRegistry& registry);
// Registers the analysis blocks (ztv); schema/AnalysisSchema.cpp.
void addAnalysisSchema(SchemaRegistry& registry);
// The `buildings` and `objects` source kinds (ObjectsSchema.cpp).
void addObjectsSchema(SchemaRegistry& registry);
// `planted`, `growth`, `phenology` (plants, plant_model) and render `date` (SeasonsSchema.cpp).
void addSeasonsSchema(SchemaRegistry& registry);
// The `photo` block of photomontages (PhotoSchema.cpp).
void addPhotoSchema(SchemaRegistry& registry);
// wireline_color, skyline_color and line_width: the photo block's and the wireline
// compare's (PhotoSchema.cpp).
std::vector<AttributeSchema> wirelineAttributes();

}  // namespace sylva
