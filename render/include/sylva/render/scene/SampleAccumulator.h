// SampleAccumulator: anti-aliasing of batch images by accumulation (Haeberli & Akeley
// 1990, "The accumulation buffer"): the scene is rendered `samples` times, each time with
// the projection shifted by a sub-pixel offset of a fixed pattern, shaded, and the shaded
// images are averaged in linear light with equal weights (a box filter over the pixel).
// With a square number of samples s² the pattern is the ordered s × s grid of sub-pixel
// centres, so the result equals the s-times larger image box-filtered down to the pixel.
//
// Chosen over a supersampled G-buffer (render at s× the size, shade, downsample): that
// needs s² times the G-buffer memory (16 samples at 3840 × 2160 would be 2.6 GB of
// G-buffer) and cannot give a non-square sample count; accumulation costs one image's
// memory plus two RGBA32F sums, and its time is the same N × (geometry + shading).
//
// Colour spaces: the display image (attachment 0 of the shading pass, sRGB-encoded RGBA8)
// is decoded to linear light before it is added and encoded again by resolve(), so edges
// are averaged after tone mapping (as the eye sees them, no dark fringes at the sun);
// the radiance (attachment 1, radiance × exposure, EXR output) is averaged as it is.
// Deterministic: fixed offsets, fixed order of additions.
//
// Ownership: owns its programs and its accumulation framebuffer; create(), begin(), add()
// and resolve() need the GL context current that create() ran in. Failures (shader or
// framebuffer creation) are Result errors; sample counts outside 1..kMaxSamples are
// programmer errors (SYLVA_CHECK) — callers check user input first.
#pragma once

#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "sylva/core/base/Result.h"
#include "sylva/render/gl/Framebuffer.h"
#include "sylva/render/gl/GlHandle.h"
#include "sylva/render/gl/ShaderLibrary.h"
#include "sylva/render/gl/ShaderProgram.h"

namespace sylva::render {

class SampleAccumulator {
public:
    static constexpr int kMaxSamples = 16;

    static Result<std::unique_ptr<SampleAccumulator>> create(const ShaderLibrary& library);

    // The sub-pixel offsets of `samples` samples (1..kMaxSamples), in pixels from the pixel
    // centre, each coordinate in (−0.5, 0.5): one sample is the centre; a square count s²
    // the ordered s × s grid; any other count N the rank-1 lattice
    // ((i + ½)/N, ((i·k mod N) + ½)/N) − ½ with k the integer coprime to N nearest N/φ
    // (a Fibonacci lattice: one sample per row and column, evenly spread).
    static std::vector<glm::dvec2> pattern(int samples);

    // `projection` (as SceneRenderer::projection, w = −z) shifted so that the image moves
    // by `offset` pixels (x right, y up) on a width × height image.
    static glm::dmat4 shifted(const glm::dmat4& projection, const glm::dvec2& offset, int width,
                              int height);

    // Clears the sums for a width × height image; `linear`: also sum radiance.
    Status begin(int width, int height, bool linear);
    // Adds `shaded` (the shading pass's target: attachment 0 sRGB RGBA8, attachment 1
    // radiance when begin() had `linear`) with `weight` (1 / samples).
    void add(const Framebuffer& shaded, float weight);
    // Writes the sums into `target` (same size and attachments as `shaded` above): the
    // averaged display colour sRGB-encoded, the averaged radiance.
    void resolve(const Framebuffer& target);

private:
    SampleAccumulator() = default;
    void drawFullScreen() const;

    ShaderProgram accumulate_;
    ShaderProgram resolve_;
    GlVertexArray emptyVertexArray_;
    Framebuffer sums_;
    bool linear_ = false;
};

}  // namespace sylva::render
