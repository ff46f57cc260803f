// SyntheticPlant: a deterministic test plant for the LoD builder until the importer and
// the procedural generator land: a recursive branch skeleton (trunk, laterals, twigs)
// with cylinder meshes, and alpha-masked leaf quads scattered in clusters around the
// twig tips. Metres, +Z up, the trunk base at the origin.
#pragma once

#include <cstdint>

#include "sylva/core/plantlod/PlantModel.h"

namespace sylva {

// `leafCount` leaves (exactly), skeleton depth chosen so that every tip carries about
// 40 leaves. The same seed always gives the same model.
PlantModel makeSyntheticPlant(int leafCount, std::uint32_t seed);

}  // namespace sylva
