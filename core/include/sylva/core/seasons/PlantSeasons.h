// PlantSeasons: the season and growth attributes of a `plants` block — `planted`,
// `growth` (GrowthCurve) and the per-species `phenology` table that overrides the
// species' default habit (the plant_model's `phenology`, else its preset's):
//     phenology = { birch = deciduous,
//                   oak = { leaf_out = "04-25", leaf_fall = "11-20", winter_leaves = 10%,
//                           autumn_colour = #8A5A2B } }
// Entry keys: type (deciduous | evergreen | palm: the table started from), leaf_out,
// full_leaf, colouring, leaf_fall ("MM-DD", northern hemisphere), winter_leaves (a
// fraction), autumn_colour (sRGB colour), tropics (true: seasonal also within ±20°).
//
// Read by PlantsSource (graph build) and checked by the DSL when a project loads, with
// the same rules, so both report the same located errors: a malformed day, days out of
// order, a species the block does not have, a growth curve with negative values or
// non-increasing ages, growth without planted.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "sylva/core/base/Result.h"
#include "sylva/core/base/SourceLocation.h"
#include "sylva/core/model/ProjectModel.h"
#include "sylva/core/seasons/GrowthCurve.h"
#include "sylva/core/seasons/Phenology.h"
#include "sylva/core/seasons/PlantDate.h"

namespace sylva {

class PlantSeasons {
public:
    // One species' entry of the phenology table: the fields written.
    struct Override {
        std::string species;
        std::optional<LeafHabit> habit;
        std::optional<double> leafOut, fullLeaf, colouring, leafFall, winterLeaves;
        std::optional<glm::vec3> autumnColour;  // linear RGB
        std::optional<bool> seasonalInTropics;
        SourceLocation location;  // of the entry's value
    };

    // Reads the block's planted, growth and phenology. `species`: the block's species
    // names (for the unknown-species check). On failure `problem` receives the location
    // of the offending value and the message does not include it.
    static Result<PlantSeasons> read(const Block& block, const std::vector<std::string>& species,
                                     SourceLocation* problem);
    // Plants planted on `planted` growing by `growth` (no phenology overrides).
    static PlantSeasons planting(const PlantDate& planted, GrowthCurve growth);
    // The species names a plants block declares: the keys of `species`, then the values
    // of `species_map` (as PlantsSource orders them).
    static std::vector<std::string> speciesOf(const Block& block);

    const std::optional<PlantDate>& planted() const { return planted_; }
    const GrowthCurve& growth() const { return growth_; }  // standard() without `growth`
    // The table of `species`: its override (if any) over the preset of `defaultHabit`.
    Phenology phenologyOf(const std::string& species, LeafHabit defaultHabit) const;
    // The size of an instance planted on planted() at `date` for a model `modelHeight`
    // metres tall: nullopt when it is not planted yet; full size (1, 1) without `planted`.
    std::optional<GrowthScale> scaleAt(const PlantDate& date, double modelHeight) const;

private:
    std::optional<PlantDate> planted_;
    GrowthCurve growth_ = GrowthCurve::standard();
    std::vector<Override> overrides_;
};

}  // namespace sylva
