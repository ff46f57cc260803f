// ProposalTargets: the targets of a ZTV taken from the proposal itself (`ztv { proposal =
// [@turbines] }`): every model an `objects` source places is one target, at the highest
// point it can reach. Parts that turn about a non-vertical axis (a rotor) are swept
// through a full turn, so a turbine's target is its blade tip at twelve o'clock whatever
// its `rotor_angle`; parts turning about a vertical axis (a nacelle's yaw) and static
// parts count as posed. Parent parts' sweeps are not combined (one turning part per
// chain, the nearest): conservative for a rotor under a yawing nacelle, which is the
// case that matters.
//
// Frames: positions are WGS84 geodetic (radians); `height` is metres above the model's
// origin along the local up (for a turbine: the tip height above its base), which the ZTV
// stands on its own DEM, as a planner states a tip height. A model raised by the objects
// source's `height` counts from its raised origin (the raise is not part of the model);
// the renderer's ground under the model (its `elevation` source) may differ from the
// ZTV's DEM, and the ZTV's DEM is the one that counts.
//
// Failures (Result errors): the source's own errors (features, model file; MeshSource's
// error contract), a source without placed models, a model with nothing above its origin.
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "sylva/core/analysis/Viewshed.h"
#include "sylva/core/base/Result.h"
#include "sylva/core/sources/objects/MeshSource.h"
#include "sylva/core/tiles/TileProvider.h"

namespace sylva {

struct ProposalTop {
    std::string label;        // "<source> feature <id>" (or "<source> placement <n>")
    double latitude = 0.0;    // radians
    double longitude = 0.0;   // radians
    double height = 0.0;      // highest point above the model's origin, metres
    double x = 0.0, y = 0.0;  // in the analysis grid's CRS, metres (filled by planZtv)
};

// Height (metres, along `up`, a unit ECEF vector) of the highest point of `model` placed by
// `placement` above the placement's origin, turning parts swept as described above.
double highestPointAbove(const MeshModel& model, const ModelPlacement& placement,
                         const glm::dvec3& up);

// Every placement of `source` (all its tiles), in feature order within a tile.
Result<std::vector<ProposalTop>> proposalTops(const std::string& sourceName,
                                              const MeshSource& source, TileProvider& provider);

}  // namespace sylva
