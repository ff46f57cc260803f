// VegetationStream: the plant instances around the camera, streamed tile by tile from
// `plants` sources through the same TileProvider (Scheduler) as the terrain's tiles
// (issue 7, seed 001 §6.1). Each frame it picks the instance tiles within the distance
// at which the largest plant still covers `minimumPixels`: tiles of a coarse level
// (about a quarter of that distance across) refined near the camera, up to two levels
// finer, so near tiles arrive first and culling is finer where it matters. Instance
// tiles of different levels hold exactly the union of their children's instances, so
// mixing levels never duplicates or drops a plant. Ready tiles become InstanceBatches
// (cached while in use); tiles not wanted for a few frames are dropped.
//
// Batch rendering waits for every wanted tile (the image is then independent of thread
// timing); interactive use draws what is ready and requests the rest.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "sylva/core/base/Result.h"
#include "sylva/core/scene/Camera.h"
#include "sylva/core/seasons/PlantDate.h"
#include "sylva/core/sources/plants/PlantsSource.h"
#include "sylva/core/vegetation/LodSelector.h"

namespace sylva {

struct VegetationStreamLayer {
    const PlantsSource* source = nullptr;
    // Per species name of the source (PlantsSource::speciesNames()): the renderer's
    // species index, or -1 when the species has no model (its instances are skipped).
    std::vector<int> species;
};

struct VegetationStreamSettings {
    double pixelAngle = 1e-3;        // radians per pixel
    double minimumPixels = 1.5;      // plants smaller than this are not streamed
    double maximumDistance = 0.0;    // metres; 0 = kDefaultDistance
    double heightAboveGround = 0.0;  // metres, the camera's
    bool wait = true;                // produce every wanted tile before returning
    // The date plants are shown at: instances of a plants source with `planted` are
    // scaled by its growth curve for their age then (absent before planting). None: full
    // size. Changing it rebuilds the cached batches.
    std::optional<PlantDate> date;
    static constexpr double kDefaultDistance = 6000.0;
};

struct VegetationStreamStatistics {
    std::size_t wantedTiles = 0;
    std::size_t readyTiles = 0;
    std::size_t instances = 0;
    double distance = 0.0;  // metres: the streaming radius used
};

class VegetationStream {
public:
    // The batches to draw this frame (owned by the stream, valid until the next
    // update). Fails when a wanted tile fails (the error names source and tile).
    Result<std::vector<const InstanceBatch*>> update(
        const std::vector<VegetationStreamLayer>& layers, TileProvider& provider,
        const Camera& camera, const std::vector<SpeciesLod>& species,
        const VegetationStreamSettings& settings);

    const VegetationStreamStatistics& statistics() const { return statistics_; }
    // Forgets the cached batches (they hold only the species known when they were made):
    // after a species' asset arrives, the next update rebuilds them with its plants.
    void clear() { batches_.clear(); }

    // Scales `placement` by the growth of `seasons` on `date` (issue 21 item 3): the crown
    // fraction on every axis, the height over the crown fraction once more on the up axis
    // (InstancePlacement::heightScale), for a model `modelHeight` metres tall. False when
    // the plant is not planted yet or under a thousandth of its size (not drawn). Public
    // for tests.
    static bool grow(const PlantSeasons& seasons, const PlantDate& date, double modelHeight,
                     InstancePlacement& placement);

    // The tiles (level, lonReduction 0) within `radius` metres of (latitude, longitude)
    // radians, refined near the point. Public for tests.
    static std::vector<TileKey> tilesAround(double latitude, double longitude, double radius,
                                            int minimumLevel);

private:
    struct Entry {
        std::shared_ptr<const InstanceBatch> batch;
        std::uint64_t lastUsed = 0;
    };
    std::map<std::pair<const PlantsSource*, TileKey>, Entry> batches_;
    std::uint64_t frame_ = 0;
    std::string dateOfBatches_;  // PlantDate::text() the cached batches were grown for
    VegetationStreamStatistics statistics_;
};

}  // namespace sylva
