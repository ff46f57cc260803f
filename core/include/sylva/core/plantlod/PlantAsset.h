// PlantAsset: everything the vegetation renderer draws for one species — the source
// model (full mesh with alpha-tested leaves, for close-ups) and its LoD (ellipsoid and
// line arrays, seed 001 §6.2; billboard clouds when they were built, for comparison).
//
// Produced once per model by a `plant_model` source (PlantModelSource) and shared,
// immutable, by every renderer and thread: hold it through std::shared_ptr<const>.
// Frame: the model's (metres, +Z up, stem base at the origin). Colours: linear RGB.
#pragma once

#include <string>

#include "sylva/core/plantlod/PlantLod.h"
#include "sylva/core/plantlod/PlantModel.h"

namespace sylva {

struct PlantAsset {
    std::string name;  // the plant_model source's name (= the species name)
    PlantModel model;  // the source mesh
    PlantLod lod;      // levels, sequential primitive arrays (and billboard clouds)
};

}  // namespace sylva
