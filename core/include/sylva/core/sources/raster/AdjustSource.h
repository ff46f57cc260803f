// AdjustSource (`source x : adjust`): per-texel colour corrections of an image.
// Colour space: the operations act on sRGB-encoded values in [0, 1] (what image
// editors show and users tune by eye): the linear input is encoded, adjusted, clamped
// and decoded back to linear RGB. Order: levels (black/white point), gamma
// (v^(1/gamma)), brightness (+), contrast (about 0.5), saturation and hue (rotation of
// the chroma about the grey axis, keeping Rec. 709 luma; hue rotation by Rodrigues'
// formula about (1,1,1)/sqrt 3). Alpha passes through. Fails only when its input fails.
#pragma once

#include <glm/glm.hpp>

#include "sylva/core/sources/Source.h"
#include "sylva/core/sources/SourceBuildContext.h"

namespace sylva {

struct AdjustParameters {
    double brightness = 0.0;
    double contrast = 1.0;
    double saturation = 1.0;
    double hue = 0.0;  // radians
    double gamma = 1.0;
    double black = 0.0;
    double white = 1.0;
};

class AdjustSource final : public Source {
public:
    // `input` must be an image source.
    AdjustSource(std::string name, const Source* input, const AdjustParameters& parameters);

    static Result<std::unique_ptr<Source>> create(const SourceBuildContext& context);

    Result<TilePointer> produce(const TileKey& key, TileProvider& provider) const override;

    // The adjustment of one linear RGB colour (exposed for tests).
    glm::vec3 apply(const glm::vec3& linear) const;

private:
    const Source* input_;
    AdjustParameters parameters_;
};

}  // namespace sylva
