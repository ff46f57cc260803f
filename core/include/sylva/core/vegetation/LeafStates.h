// leafStates: the season of every species the vegetation renderer draws, for one view
// (issue 21 item 3). Each renderer species takes the phenology table of the first
// plants layer that draws it (PlantsSource::phenology()); the state is evaluated at the
// render date and the camera's latitude (one latitude per view: across the few
// kilometres plants are drawn, the season does not change).
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "sylva/core/seasons/Phenology.h"
#include "sylva/core/seasons/PlantDate.h"
#include "sylva/core/vegetation/VegetationStream.h"

namespace sylva {

// One per table, in order: tables[i].at(*date, latitude) (`latitude` in radians); without
// a date every entry is full leaf (LeafState{}). Never fails. The far-field canopy
// (render/vegetation/FarFieldCanopy) evaluates its dominant source's tables with it, so
// its crowns take the season the drawn trees take.
std::vector<LeafState> leafStatesOf(const std::vector<Phenology>& tables,
                                    const std::optional<PlantDate>& date, double latitude);

// Per renderer species (0 … speciesCount − 1). Without a date every species is in full
// leaf (LeafState{}); a species no layer draws too. `latitude` in radians.
std::vector<LeafState> leafStates(const std::vector<VegetationStreamLayer>& layers,
                                  std::size_t speciesCount, const std::optional<PlantDate>& date,
                                  double latitude);

}  // namespace sylva
