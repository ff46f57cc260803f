// FarFieldFade: the uniforms of shaders/vegetation/farfield_fade.glsl, the screen-door
// hand-over from the drawn trees to the far-field canopy. Both the vegetation shaders
// (which drop their fragments where the canopy takes the pixel) and the canopy shader
// (which drops the rest) get the same values for a frame, so the two tests are
// complementary pixel by pixel.
#pragma once

#include <glm/glm.hpp>

#include "sylva/render/gl/ShaderProgram.h"

namespace sylva::render {

struct FarFieldFade {
    double start = 0.0;  // metres from the camera where the canopy begins to take pixels
    double end = 0.0;    // metres where it has all of them; end <= start: no far field

    bool enabled() const { return end > start; }
    // Sets uFarFieldFade and uFarFieldRay of `program` for a reversed-Z `projection`
    // (SceneRenderer::projection, possibly shifted per anti-aliasing sample) with near
    // plane `near` metres on a width × height pixel target.
    void apply(ShaderProgram& program, const glm::dmat4& projection, double near, int width,
               int height) const;
};

}  // namespace sylva::render
