// BuildingsSource (`source x : buildings`): polygon footprints from a `features` source
// extruded from the terrain (see MeshSource for the access path and the error contract).
//
// Per building: the ground is sampled (GroundSampler, bilinear at MeshSource::kGroundLevel)
// at every ring vertex, every edge midpoint and the centroid; the base is the lowest (or
// the mean) of those heights, the walls run from 0.5 m below the lowest sample (so no
// wall floats over a dip between samples) up to the eaves at base + height, and the roof
// (flat, gable, hip, pyramid) sits on the eaves (BuildingExtruder). Height: the height
// attribute, else floors × storey height, else the constant. A multi-polygon gives one
// building per outer ring (with the holes that follow it).
#pragma once

#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "sylva/core/sources/SourceBuildContext.h"
#include "sylva/core/sources/objects/MeshSource.h"
#include "sylva/core/sources/vector/FeatureSource.h"

namespace sylva {

enum class RoofKind;

struct BuildingsParameters {
    double height = 10.0;               // metres, eaves above the base when no attribute gives it
    std::string heightAttribute;        // metres
    std::string floorsAttribute;        // number of floors (× storeyHeight)
    double storeyHeight = 3.0;          // metres
    bool meanBase = false;              // base at the mean (true) or lowest (false) ground height
    std::string roof = "flat";          // flat, gable, hip, pyramid
    std::string roofAttribute;          // values as `roof`
    double pitch = 0.5235987755982988;  // radians
    std::string pitchAttribute;         // degrees
    glm::vec3 wallColor{0.85f, 0.82f, 0.76f};            // sRGB
    glm::vec3 roofColor{0.62f, 0.27f, 0.2f};             // sRGB
    std::string wallColorAttribute, roofColorAttribute;  // "#rrggbb"
};

class BuildingsSource final : public MeshSource {
public:
    BuildingsSource(std::string name, const FeatureSource* features, const Source* elevation,
                    BuildingsParameters parameters);
    ~BuildingsSource() override;

    static Result<std::unique_ptr<Source>> create(const SourceBuildContext& context);

    Result<GeographicBounds> bounds() const override;
    Result<std::shared_ptr<const MeshTile>> tile(const TileKey& key,
                                                 TileProvider& provider) const override;
    // The keys of every non-empty tile (for benchmarks and tools); fails as bounds().
    Result<std::vector<TileKey>> tileKeys() const;

    struct Prepared;  // the checked buildings, by tile (BuildingsSource.cpp)

private:
    Result<std::shared_ptr<const Prepared>> prepared() const;

    const FeatureSource* features_;
    const Source* elevation_;
    BuildingsParameters parameters_;
    mutable std::mutex mutex_;
    mutable std::shared_ptr<const Prepared> prepared_;
    mutable std::optional<Error> failure_;
};

}  // namespace sylva
