// PlantCrowns: the crowns of a `plants` source as screens of a screened ZTV or a shadow
// study (`screening = [@forest_plants]`): every instance the source scatters over the
// study's area becomes a column as tall as its tree (the species model's height × the
// instance scale) over a disc of its crown radius (the model's largest horizontal reach
// from the stem × scale), like a canopy height model made from the drawn forest. The
// instances are the ones the renderer draws (same source, same seed), so the screened
// ZTV and the images agree about where the trees stand.
//
// Frames: latitude/longitude WGS84 radians; heights and radii metres; x, y in the analysis
// grid's CRS (filled by the study's plan).
//
// Failures (Result errors): a plants source without `models` (its trees have no height),
// a model that cannot be built or read (PlantModelSource::asset), an input tile failure.
#pragma once

#include <string>
#include <vector>

#include "sylva/core/base/Result.h"
#include "sylva/core/sources/plants/PlantsSource.h"
#include "sylva/core/sources/vector/FeatureCollection.h"
#include "sylva/core/tiles/TileProvider.h"

namespace sylva {

struct PlantCrown {
    double latitude = 0.0;    // radians
    double longitude = 0.0;   // radians
    double height = 0.0;      // crown top above the ground at the stem, metres
    double radius = 0.0;      // metres
    double x = 0.0, y = 0.0;  // analysis grid CRS, metres
};

// The instances of `source` inside `area` (radians), at the source's coarsest instance
// level (fewest tiles; a tile's instances do not depend on the level asked).
Result<std::vector<PlantCrown>> plantCrowns(const std::string& sourceName,
                                            const PlantsSource& source,
                                            const GeographicBounds& area, TileProvider& provider);

}  // namespace sylva
