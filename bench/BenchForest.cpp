#include "BenchForest.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "sylva/core/geo/Ellipsoid.h"
#include "sylva/core/plantlod/BillboardCloudBuilder.h"
#include "sylva/core/plantlod/PlantGenerator.h"
#include "sylva/core/plantlod/PlantLodBuilder.h"

namespace sylva::bench {

namespace {
constexpr double kDegree = std::numbers::pi / 180;
}  // namespace

// Overview → descent → inside the forest → turn. The first group is at the centre.
const std::vector<PathKey> kForestPath = {
    {-2600.0, 0.0, 700.0, 0.0, -14.0 * kDegree},  // overview
    {-1500.0, 0.0, 450.0, 0.0, -16.0 * kDegree},  // descent starts
    {-160.0, 0.0, 12.0, 0.0, -2.0 * kDegree},     // at the forest edge
    {-20.0, 0.0, 1.7, 0.0, 0.0},                  // inside the forest
    {-20.0, 0.0, 1.7, std::numbers::pi, 0.0},     // turned around
};

Camera forestCamera(const std::vector<PathKey>& keys, double t) {
    const double clamped = std::clamp(t, 0.0, double(keys.size() - 1));
    const std::size_t i = std::min(std::size_t(clamped), keys.size() - 2);
    const double u = clamped - double(i);
    const PathKey& a = keys[i];
    const PathKey& b = keys[i + 1];
    const auto mix = [u](double x, double y) { return x + (y - x) * u; };
    Camera c;
    c.geodetic.latitude = kForestLatitude + mix(a.north, b.north) / kMetresPerRadian;
    c.geodetic.longitude =
        kForestLongitude + mix(a.east, b.east) / (kMetresPerRadian * std::cos(kForestLatitude));
    c.geodetic.height = kForestGround + mix(a.height, b.height);
    c.position = Ellipsoid::toEcef(c.geodetic);
    c.axes =
        Camera::axesFromAngles(c.geodetic, mix(a.heading, b.heading), mix(a.pitch, b.pitch), 0.0);
    c.verticalFov = 50.0 * kDegree;
    return c;
}

// Forest groups of about 1,000 trees each (jittered 7 m grid in a disc of ~125 m radius),
// group centres on a jittered grid `spacing` metres apart around the origin.
std::vector<InstanceBatch> makeForest(int trees, std::uint32_t species,
                                      const std::vector<SpeciesLod>& lods, std::uint32_t seed) {
    std::mt19937 random(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const int groups = std::max(1, (trees + 999) / 1000);
    const int side = int(std::ceil(std::sqrt(double(groups))));
    const double spacing = 400.0;
    // Grid cells nearest to the origin first: the first group sits at the centre.
    std::vector<glm::ivec2> cellsByDistance;
    for (int i = 0; i < side * side; ++i) {
        cellsByDistance.emplace_back(i % side - side / 2, i / side - side / 2);
    }
    std::stable_sort(
        cellsByDistance.begin(), cellsByDistance.end(),
        [](glm::ivec2 a, glm::ivec2 b) { return a.x * a.x + a.y * a.y < b.x * b.x + b.y * b.y; });
    std::vector<InstanceBatch> batches;
    int remaining = trees;
    for (int g = 0; g < groups; ++g) {
        const double jitter = g == 0 ? 0.0 : 1.0;
        const double gx = cellsByDistance[g].x * spacing + (unit(random) - 0.5) * 80.0 * jitter;
        const double gy = cellsByDistance[g].y * spacing + (unit(random) - 0.5) * 80.0 * jitter;
        const int count = std::min(remaining, 1000);
        remaining -= count;
        std::vector<InstancePlacement> placements;
        const double cell = 7.0;
        const int cells = int(std::ceil(std::sqrt(count / (std::numbers::pi / 4)))) + 1;
        for (int iy = 0; iy < cells && int(placements.size()) < count; ++iy) {
            for (int ix = 0; ix < cells && int(placements.size()) < count; ++ix) {
                const double x = (ix - cells * 0.5 + unit(random)) * cell;
                const double y = (iy - cells * 0.5 + unit(random)) * cell;
                if (x * x + y * y > std::pow(cells * 0.5 * cell, 2)) {
                    continue;
                }
                InstancePlacement p;
                p.latitude = kForestLatitude + (gy + y) / kMetresPerRadian;
                p.longitude =
                    kForestLongitude + (gx + x) / (kMetresPerRadian * std::cos(kForestLatitude));
                // Sunk 0.2 m so that stems stand in the ground.
                p.baseEcef = Ellipsoid::toEcef({p.latitude, p.longitude, kForestGround - 0.2});
                p.heading = float(unit(random) * 2 * std::numbers::pi);
                p.scale = float(0.8 + 0.4 * unit(random));
                p.tint = glm::vec3(float(0.85 + 0.3 * unit(random)));
                p.species = species;
                placements.push_back(p);
            }
        }
        const glm::dvec3 origin = Ellipsoid::toEcef(
            {kForestLatitude + gy / kMetresPerRadian,
             kForestLongitude + gx / (kMetresPerRadian * std::cos(kForestLatitude)),
             kForestGround});
        batches.push_back(LodSelector::makeBatch(origin, placements, lods));
    }
    return batches;
}

std::vector<const InstanceBatch*> pointers(const std::vector<InstanceBatch>& batches) {
    std::vector<const InstanceBatch*> out;
    for (const InstanceBatch& b : batches) {
        out.push_back(&b);
    }
    return out;
}

// The plant: a generated oak with `leaves` leaves, its LoD and billboard clouds.
Result<std::shared_ptr<PlantAsset>> buildOak(int leaves) {
    Result<TreeParameters> preset = PlantGenerator::preset("oak");
    if (!preset) {
        return preset.error();
    }
    PlantGeneratorOptions generatorOptions;
    generatorOptions.seed = 1;
    generatorOptions.leafCount = leaves;
    Result<PlantModel> model = PlantGenerator::generate(preset.value(), generatorOptions);
    if (!model) {
        return model.error();
    }
    Result<PlantLod> lod = buildPlantLod(model.value(), PlantLodOptions{});
    if (!lod) {
        return lod.error();
    }
    if (Status billboards = addBillboardClouds(model.value(), lod.value(), PlantLodOptions{});
        !billboards) {
        return billboards.error();
    }
    auto asset = std::make_shared<PlantAsset>();
    asset->name = "oak";
    asset->model = std::move(model.value());
    asset->lod = std::move(lod.value());
    return asset;
}

}  // namespace sylva::bench
