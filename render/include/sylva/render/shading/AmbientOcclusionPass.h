// AmbientOcclusionPass: screen-space ambient occlusion over the G-buffer (seed 001 §7.1,
// the horizon-based SSAO of Bavoil and Sainz 2008; shaders/shading/ambient_occlusion.frag
// and its depth-aware blur). The result, an R16F texture of the G-buffer's size, is the
// unoccluded fraction of each pixel's hemisphere (1 open ground and sky, 0.5 at the foot
// of an infinitely high wall); the shading pass multiplies the sky light by it and by the
// G-buffer's own occlusion (albedo.a), never the sun.
//
// Needs a current GL 4.5 context for create(), run() and the destructor (RAII textures).
// Shader errors come back from create(); bad settings are programmer errors (the DSL
// checks the user's values: radius 0.1..100 m, strength 0..1).
#pragma once

#include <cstdint>
#include <memory>

#include <glm/glm.hpp>

#include "sylva/core/base/Result.h"
#include "sylva/render/gl/Framebuffer.h"
#include "sylva/render/gl/GlHandle.h"
#include "sylva/render/gl/ShaderLibrary.h"
#include "sylva/render/gl/ShaderProgram.h"

namespace sylva::render {

struct AmbientOcclusionSettings {
    // render { ambient_occlusion }: on by default (seed 001 §7.1 computes it for every
    // surface without a precomputed term: terrain, buildings, models).
    bool enabled = true;
    double radius = 2.0;    // metres: the sphere around a point searched for occluders
    double strength = 1.0;  // 0..1: 1 - strength x the occluded hemisphere fraction
};

class AmbientOcclusionPass {
public:
    static Result<std::unique_ptr<AmbientOcclusionPass>> create(const ShaderLibrary& library);

    // Computes the occlusion of `gbuffer` (attachment 1 view-space normals, reversed-Z
    // depth; `projection` and `near` as it was drawn with). Returns the texture (owned by
    // the pass, valid until the next run or a size change). Leaves framebuffer 0 bound.
    // The sphere is searched up to a screen radius of a quarter of the image height (nearer
    // than that, the effective radius shrinks: a walker's feet are not searched 2 m wide).
    Result<std::uint32_t> run(const Framebuffer& gbuffer, const glm::dmat4& projection, double near,
                              const AmbientOcclusionSettings& settings);

private:
    AmbientOcclusionPass() = default;
    Status ensureTargets(int width, int height);

    ShaderProgram occlusion_;
    ShaderProgram blur_;
    GlVertexArray emptyVertexArray_;  // full-screen triangle: no attributes
    Framebuffer raw_;                 // R16F, before the blur
    Framebuffer blurred_;             // R16F, the result
};

}  // namespace sylva::render
