// Example: use sylva_core as a library without any project file or GL. Builds a
// small source graph by hand (noise relief -> hypsometric colour), evaluates one
// tile of the pyramid and prints a few texels.
//
//   sylva_example_tile_dump [level] [x] [y]
#include <cstdio>
#include <cstdlib>

#include "sylva/core/scheduler/TileEvaluator.h"
#include "sylva/core/sources/raster/HypsometricSource.h"
#include "sylva/core/sources/raster/NoiseSource.h"

int main(int argc, char** argv) {
    sylva::TileKey key{argc > 1 ? std::atoi(argv[1]) : 3, 0, argc > 2 ? std::atoi(argv[2]) : 9,
                       argc > 3 ? std::atoi(argv[3]) : 2};
    if (!key.valid()) {
        std::fprintf(stderr, "tile_dump: invalid tile %s\n", key.toString().c_str());
        return 2;
    }
    sylva::NoiseSource relief("relief", sylva::NoiseParameters{});
    sylva::HypsometricParameters colours;
    colours.water = {0.01f, 0.03f, 0.08f};
    colours.shallowWater = {0.02f, 0.08f, 0.15f};
    colours.rock = {0.15f, 0.13f, 0.11f};
    sylva::HypsometricSource colour("colour", &relief, nullptr, colours);

    sylva::TileEvaluator evaluator(sylva::TileFormat{64, 2});
    sylva::Result<sylva::TilePointer> height = evaluator.tile(relief, key);
    sylva::Result<sylva::TilePointer> rgb = evaluator.tile(colour, key);
    if (!height || !rgb) {
        std::fprintf(stderr, "tile_dump: %s\n",
                     (!height ? height.error() : rgb.error()).message.c_str());
        return 1;
    }
    std::printf("tile %s: lon [%.4f, %.4f] lat [%.4f, %.4f] rad\n", key.toString().c_str(),
                key.west(), key.east(), key.south(), key.north());
    for (int i = 0; i < 64; i += 16) {
        std::printf("  texel (%2d,%2d): height %8.1f m, linear rgb %.3f %.3f %.3f\n", i, i,
                    height.value()->at(i, i, 0), rgb.value()->at(i, i, 0), rgb.value()->at(i, i, 1),
                    rgb.value()->at(i, i, 2));
    }
    std::printf("tiles produced: %zu in %.3f s\n", evaluator.statistics().misses,
                evaluator.statistics().produceSeconds);
    return 0;
}
