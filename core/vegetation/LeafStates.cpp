#include "sylva/core/vegetation/LeafStates.h"

namespace sylva {

std::vector<LeafState> leafStatesOf(const std::vector<Phenology>& tables,
                                    const std::optional<PlantDate>& date, double latitude) {
    std::vector<LeafState> states(tables.size());
    if (date) {
        for (std::size_t i = 0; i < tables.size(); ++i) {
            states[i] = tables[i].at(*date, latitude);
        }
    }
    return states;
}

std::vector<LeafState> leafStates(const std::vector<VegetationStreamLayer>& layers,
                                  std::size_t speciesCount, const std::optional<PlantDate>& date,
                                  double latitude) {
    std::vector<LeafState> states(speciesCount);
    if (!date) {
        return states;
    }
    std::vector<bool> done(speciesCount, false);
    for (const VegetationStreamLayer& layer : layers) {
        const std::vector<LeafState> layerStates =
            leafStatesOf(layer.source->phenology(), date, latitude);
        for (std::size_t i = 0; i < layer.species.size() && i < layerStates.size(); ++i) {
            const int species = layer.species[i];
            if (species < 0 || std::size_t(species) >= speciesCount || done[species]) {
                continue;
            }
            states[species] = layerStates[i];
            done[species] = true;
        }
    }
    return states;
}

}  // namespace sylva
