// Framebuffer: an off-screen FBO with N colour texture attachments of given internal
// formats (GL_RGBA8, GL_RGBA32F, ...) and an optional GL_DEPTH_COMPONENT32F depth texture,
// plus read-back helpers for tests and image output.
//
// Ownership: move-only RAII; owns the FBO and its textures and deletes them in the
// destructor, so it must be destroyed while its GL context is still alive (and current).
// Every call needs that context current on the calling thread.
//
// Failures: create() returns an Error for bad sizes, formats the driver rejects and
// incomplete framebuffers. Out-of-range attachment indices are programmer errors and abort
// through SYLVA_CHECK. Read-backs return rows top to bottom (flipped from GL's bottom-up
// order), so row 0 is the top of the image.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec4.hpp>

#include "sylva/core/base/Result.h"
#include "sylva/render/gl/GlHandle.h"

namespace sylva::render {

class Framebuffer {
public:
    // colorFormats: sized internal formats (GLenum values), one per attachment, in
    // GL_COLOR_ATTACHMENT0 + i order; all are enabled as draw buffers.
    static Result<Framebuffer> create(int width, int height,
                                      const std::vector<std::uint32_t>& colorFormats,
                                      bool withDepth);

    Framebuffer() = default;  // empty: id() == 0
    // Moved-from framebuffers are empty (no attachments, size 0).
    Framebuffer(Framebuffer&& other) noexcept;
    Framebuffer& operator=(Framebuffer&& other) noexcept;
    Framebuffer(const Framebuffer&) = delete;
    Framebuffer& operator=(const Framebuffer&) = delete;

    // Binds as GL_FRAMEBUFFER (draw and read) and sets the viewport to the full size.
    void bind() const;
    // Binds the default framebuffer (0) again.
    static void unbind();

    // Clear one colour attachment / the depth attachment (no binding needed). Colours are
    // converted to the attachment's format (float attachments keep values outside 0..1).
    void clearColor(int attachment, const glm::vec4& color) const;
    void clearDepth(float depth) const;

    std::uint32_t id() const { return framebuffer_.get(); }
    int width() const { return width_; }
    int height() const { return height_; }
    int colorCount() const { return static_cast<int>(colorTextures_.size()); }
    std::uint32_t colorFormat(int index) const;
    std::uint32_t colorTexture(int index) const;
    std::uint32_t depthTexture() const { return depthTexture_.get(); }  // 0 without depth

    // Attachment `attachment` as RGBA8, width * height * 4 bytes, rows top to bottom.
    std::vector<std::uint8_t> readPixelsRGBA8(int attachment = 0) const;
    // Attachment `attachment` as floats with 1 (R), 2 (RG), 3 (RGB) or 4 (RGBA) channels,
    // width * height * channels values, rows top to bottom.
    std::vector<float> readPixelsFloat(int attachment, int channels) const;
    // The depth attachment, width * height values, rows top to bottom. Requires depth.
    std::vector<float> readDepth() const;

private:
    // Reads the bound attachment (or depth when attachment < 0) into `out`, then flips rows.
    void readInto(int attachment, std::uint32_t format, std::uint32_t type, int bytesPerPixel,
                  void* out) const;

    GlFramebuffer framebuffer_;
    std::vector<GlTexture> colorTextures_;
    std::vector<std::uint32_t> colorFormats_;
    GlTexture depthTexture_;
    int width_ = 0;
    int height_ = 0;
};

}  // namespace sylva::render
