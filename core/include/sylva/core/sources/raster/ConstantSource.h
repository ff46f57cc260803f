// ConstantSource (`source x : constant`): one elevation (metres) or one colour
// (linear RGBA, straight alpha) on every texel. Never fails.
#pragma once

#include <glm/glm.hpp>

#include "sylva/core/sources/Source.h"
#include "sylva/core/sources/SourceBuildContext.h"

namespace sylva {

class ConstantSource final : public Source {
public:
    // Elevation source of `height` metres.
    ConstantSource(std::string name, double height);
    // Image source of `linearColor` (linear RGB, alpha).
    ConstantSource(std::string name, const glm::vec4& linearColor);

    // From a `source x : constant` block (colour written in sRGB).
    static Result<std::unique_ptr<Source>> create(const SourceBuildContext& context);

    Result<TilePointer> produce(const TileKey& key, TileProvider& provider) const override;

private:
    glm::vec4 value_;  // elevation: x only
};

}  // namespace sylva
