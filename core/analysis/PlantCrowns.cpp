#include "sylva/core/analysis/PlantCrowns.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "sylva/core/base/Check.h"
#include "sylva/core/plantlod/PlantAsset.h"
#include "sylva/core/sources/plants/PlantModelSource.h"

namespace sylva {

namespace {

struct SpeciesSize {
    double height = 0.0;  // metres, scale 1
    double radius = 0.0;  // metres, scale 1
};

// Height and crown reach of every species of the source, from its plant models.
Result<std::vector<SpeciesSize>> speciesSizes(const std::string& sourceName,
                                              const PlantsSource& source) {
    std::vector<SpeciesSize> sizes;
    for (std::size_t s = 0; s < source.speciesNames().size(); ++s) {
        const PlantModelSource* model = s < source.models().size() ? source.models()[s] : nullptr;
        if (model == nullptr)
            return Error{"'" + sourceName +
                         "' has no `models`: its trees have no height to screen with (list the "
                         "plant_model sources of its species)"};
        auto asset = model->asset();
        if (!asset)
            return asset.error();
        const glm::vec3 low = (*asset)->model.boundsMinimum();
        const glm::vec3 high = (*asset)->model.boundsMaximum();
        SpeciesSize size;
        size.height = std::max(0.0f, high.z);
        size.radius =
            std::max({std::abs(low.x), std::abs(high.x), std::abs(low.y), std::abs(high.y)});
        sizes.push_back(size);
    }
    return sizes;
}

// The tile of (level, reduction 0) holding a point, clamped to the grid.
std::pair<int, int> cellOf(int level, double longitude, double latitude) {
    const double pi = std::numbers::pi;
    const int columns = TileKey::columns(level, 0), rows = TileKey::rows(level);
    const int x = std::clamp(int((longitude + pi) / (2 * pi) * columns), 0, columns - 1);
    const int y = std::clamp(int((pi / 2 - latitude) / pi * rows), 0, rows - 1);
    return {x, y};
}

}  // namespace

Result<std::vector<PlantCrown>> plantCrowns(const std::string& sourceName,
                                            const PlantsSource& source,
                                            const GeographicBounds& area, TileProvider& provider) {
    auto sizes = speciesSizes(sourceName, source);
    if (!sizes)
        return sizes.error();
    const int level = source.minimumLevel();
    const auto [west, north] = cellOf(level, area.west, area.north);
    const auto [east, south] = cellOf(level, area.east, area.south);
    std::vector<PlantCrown> crowns;
    for (int y = north; y <= south; ++y)
        for (int x = west; x <= east; ++x) {
            auto tile = source.instances(TileKey{level, 0, x, y}, provider);
            if (!tile)
                return tile.error();
            for (const PlantInstance& instance : (*tile)->instances) {
                if (instance.longitude < area.west || instance.longitude > area.east ||
                    instance.latitude < area.south || instance.latitude > area.north)
                    continue;
                const std::string& name = (*tile)->species[instance.species];
                const auto& names = source.speciesNames();
                const auto found = std::find(names.begin(), names.end(), name);
                SYLVA_CHECK(found != names.end());
                const SpeciesSize& size = (*sizes)[std::size_t(found - names.begin())];
                PlantCrown crown;
                crown.latitude = instance.latitude;
                crown.longitude = instance.longitude;
                crown.height = size.height * double(instance.scale);
                crown.radius = size.radius * double(instance.scale);
                crowns.push_back(crown);
            }
        }
    return crowns;
}

}  // namespace sylva
