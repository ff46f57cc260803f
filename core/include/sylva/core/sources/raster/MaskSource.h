// MaskSource (`source x : mask`): a Mask tile (one channel in [0, 1]) from one or
// more inputs, in three steps:
//  1. per texel: a BandExpression over the inputs' channels, clamped to [0, 1]; or,
//     with class colours, 1 where the first input's nearest class colour (squared
//     distance in linear RGB) is the selected class (the nearest-class-colour
//     classification seed 004 derives vegetation types with). Texels where an image
//     input has alpha 0 (no data) give 0.
//  2. morphology with a square structuring element of radius r texels: open (erode =
//     min filter, then dilate = max filter) and close (dilate, then erode), each as
//     separable row/column passes (Serra, Image Analysis and Mathematical Morphology).
//  3. feather: a box blur of radius r applied twice (a tent filter).
// Radii are given in metres and converted with the tile's north-south texel size on
// a sphere of the mean Earth radius. Steps 2-3 read the 3 x 3 neighbour tiles of the
// inputs so the result is seamless across tiles; radii are capped at one tile.
// Variables: `b1`..`b4` are channels of the first input, `<input name>` the first
// channel of that input, `<input name>.b1`..`.b4` or `.r .g .b .a` its channels.
// Fails when an input fails (the input's error).
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "sylva/core/sources/Source.h"
#include "sylva/core/sources/SourceBuildContext.h"
#include "sylva/core/sources/raster/BandExpression.h"

namespace sylva {

struct MaskParameters {
    std::string expression;          // used when classes is empty
    std::vector<glm::vec3> classes;  // linear RGB
    int select = 0;                  // 0-based class index
    double open = 0.0;               // metres
    double close = 0.0;              // metres
    double feather = 0.0;            // metres
};

class MaskSource final : public Source {
public:
    // Fails when the expression does not parse (message "<reason> at column <n>").
    static Result<std::unique_ptr<MaskSource>> make(std::string name,
                                                    std::vector<const Source*> inputs,
                                                    MaskParameters parameters);

    static Result<std::unique_ptr<Source>> create(const SourceBuildContext& context);

    Result<TilePointer> produce(const TileKey& key, TileProvider& provider) const override;

    // Texels per `metres` at this tile size and level (north-south).
    static int radiusTexels(double metres, int tileSize, int level);

private:
    MaskSource(std::string name, std::vector<const Source*> inputs, MaskParameters parameters,
               BandExpression expression);

    std::vector<const Source*> sources_;
    MaskParameters parameters_;
    BandExpression expression_;
};

}  // namespace sylva
