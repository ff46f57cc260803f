// The season and growth attributes of issue 21 item 3, added to existing blocks:
// `plants { planted; growth; phenology }` (read by PlantSeasons), `plant_model
// { phenology }` (the species' default habit) and `render { date }` (the date plants
// are shown at). Implementations: core/vegetation (PlantSeasons, Phenology,
// GrowthCurve, PlantDate); drawn by render/vegetation.

#include "AttributeBuilders.h"
#include "sylva/core/model/Schema.h"

namespace sylva {
namespace {

using schema::attribute;

AttributeSchema nonNegative(std::string name, Dimension dimension, std::string doc) {
    AttributeSchema a = attribute(std::move(name), ValueType::Number, std::move(doc));
    a.dimension = dimension;
    a.minimum = 0.0;
    return a;
}

void addPlantsAttributes(KindSchema& plants) {
    plants.attributes.push_back(attribute(
        "planted", ValueType::DateTime,
        "Date the plants were (or will be) planted, e.g. 2027-03-01: with `growth` they are "
        "drawn at their size for their age on the render date, and not at all before it. "
        "Without `planted` plants are drawn full grown."));
    AttributeSchema growth = attribute(
        "growth", ValueType::List,
        "Size by age since `planted` (needs it), piecewise linear: a list of points "
        "{ age = years, height = metres or size = fraction of the model's height, crown = "
        "fraction of the model's crown width (default: the point's height fraction) }, ages "
        "increasing, e.g. [{ age = 0, height = 1.5m }, { age = 15, size = 60%, crown = 55% }, "
        "{ age = 40, size = 100% }]. Before the first age the first size, after the last the "
        "last. Default with `planted`: 10% at 0, 35% at 5, 70% at 15 and 100% at 40 years.");
    growth.element = ValueType::Object;
    growth.fields = {
        nonNegative("age", Dimension::None, "Years since planting."),
        nonNegative("height", Dimension::Length, "Height in metres (or give `size`)."),
        nonNegative("size", Dimension::Ratio, "Height as a fraction of the model's height."),
        nonNegative("crown", Dimension::Ratio,
                    "Crown width as a fraction of the model's (default: the height fraction)."),
    };
    plants.attributes.push_back(std::move(growth));
    plants.attributes.push_back(attribute(
        "phenology", ValueType::Object,
        "Seasons per species, overriding each model's `phenology`: { species = deciduous | "
        "evergreen | palm, or species = { type, leaf_out, full_leaf, colouring, leaf_fall, "
        "winter_leaves, autumn_colour, tropics } }. Days are \"MM-DD\" of the northern "
        "hemisphere (shifted half a year south of the equator; defaults 04-15, 05-21, 09-25, "
        "11-10): leaves grow from leaf_out to full_leaf, turn to autumn_colour (default "
        "#B85A1E) from colouring, fall in the second half up to leaf_fall; winter_leaves "
        "(default 0%, evergreen 100%) stay in winter. Within 20 degrees of the equator every "
        "species keeps full leaf unless `tropics = true` (blending in up to 26 degrees). A "
        "species the block does not have is an error."));
}

void addPlantModelAttributes(KindSchema& plantModel) {
    AttributeSchema habit = attribute(
        "phenology", ValueType::Word,
        "Leaf habit of the species (docs/plants.md): deciduous (leaf-off in winter, autumn "
        "colour), evergreen or palm (leaves all year). Default: deciduous for the oak, birch "
        "and bush presets, palm for palm, evergreen otherwise. A plants block's `phenology` "
        "can override it per species.");
    habit.words = {"deciduous", "evergreen", "palm"};
    plantModel.attributes.push_back(std::move(habit));
}

void addRenderAttributes(KindSchema& render) {
    render.attributes.push_back(attribute(
        "date", ValueType::DateTime,
        "Date the plants are shown at (their season and their growth since `planted`), e.g. "
        "2042-07-01; a scenario sets its own with `override render { date = ... }`. Absent: "
        "the date of the view's time (views `times`); without either, plants are full grown "
        "in full leaf. The sun still follows the view's time."));
}

}  // namespace

void addSeasonsSchema(SchemaRegistry& registry) {
    if (KindSchema* plants = registry.edit("source", "plants")) {
        addPlantsAttributes(*plants);
    }
    if (KindSchema* plantModel = registry.edit("source", "plant_model")) {
        addPlantModelAttributes(*plantModel);
    }
    if (KindSchema* render = registry.edit("render")) {
        addRenderAttributes(*render);
    }
}

}  // namespace sylva
