// The vegetation benchmark's forest (`sylva bench vegetation`, also used by `sylva bench
// shading`): generated oaks in forest groups on a flat meadow at 120 m around
// (46.5°N, 7.5°E), and the scripted path overview → descent → inside the forest → turn.
#pragma once

#include <cstdint>
#include <memory>
#include <numbers>
#include <vector>

#include "sylva/core/base/Result.h"
#include "sylva/core/plantlod/PlantAsset.h"
#include "sylva/core/scene/Camera.h"
#include "sylva/core/vegetation/LodSelector.h"

namespace sylva::bench {

inline constexpr double kForestGround = 120.0;  // metres: the flat terrain
inline constexpr double kForestLatitude = 46.5 * std::numbers::pi / 180;
inline constexpr double kForestLongitude = 7.5 * std::numbers::pi / 180;
inline constexpr double kMetresPerRadian = 6367000.0;

// A path key: metres north and east of the forest centre, height above the ground,
// heading and pitch (radians).
struct PathKey {
    double north, east, height, heading, pitch;
};
// Overview → descent → inside the forest → turn (one segment between keys).
extern const std::vector<PathKey> kForestPath;

// The camera at path time `t` (0 .. keys - 1), interpolated linearly between keys.
Camera forestCamera(const std::vector<PathKey>& keys, double t);

// Forest groups of about 1,000 trees each (jittered 7 m grid in a disc of ~125 m
// radius), group centres on a jittered grid 400 m apart around the centre.
std::vector<InstanceBatch> makeForest(int trees, std::uint32_t species,
                                      const std::vector<SpeciesLod>& lods, std::uint32_t seed);
std::vector<const InstanceBatch*> pointers(const std::vector<InstanceBatch>& batches);

// The plant: a generated oak with `leaves` leaves, its LoD and billboard clouds.
Result<std::shared_ptr<PlantAsset>> buildOak(int leaves);

}  // namespace sylva::bench
