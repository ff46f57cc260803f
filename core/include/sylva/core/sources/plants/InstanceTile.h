// InstanceTile: the plant instances of one TileKey, produced by a plants source
// (PlantsSource::instances). Immutable once produced, shared as
// std::shared_ptr<const InstanceTile>.
//
// Each instance belongs to exactly one tile: the one whose half-open bounds
// [west, east) x [south, north) contain its position, so the tiles of one level
// hold every instance once.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "sylva/core/tiles/TileKey.h"

namespace sylva {

struct PlantInstance {
    double longitude = 0.0;     // radians, WGS84
    double latitude = 0.0;      // radians, WGS84
    double height = 0.0;        // metres above the ellipsoid: the terrain surface (elevation input)
    std::uint32_t species = 0;  // index into InstanceTile::species
    float scale = 1.0f;         // uniform scale of the species model
    float rotation = 0.0f;      // about the local up axis, radians, clockwise from north
    glm::vec3 tint{1.0f};       // multiplies the model's colour, linear RGB
};

struct InstanceTile {
    TileKey key;
    std::vector<std::string> species;      // species (model) names, shared by the source's tiles
    std::vector<PlantInstance> instances;  // sorted by (latitude row cell, longitude cell)
};

}  // namespace sylva
