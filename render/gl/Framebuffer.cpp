#include "sylva/render/gl/Framebuffer.h"

#include <glad/gl.h>

#include <cstdio>
#include <cstring>
#include <string>
#include <utility>

namespace sylva::render {
namespace {

std::string hex(std::uint32_t value) {
    char buffer[16];
    std::snprintf(buffer, sizeof buffer, "0x%04x", value);
    return buffer;
}

const char* statusName(GLenum status) {
    switch (status) {
        case GL_FRAMEBUFFER_UNDEFINED:
            return "GL_FRAMEBUFFER_UNDEFINED";
        case GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT:
            return "GL_FRAMEBUFFER_INCOMPLETE_ATTACHMENT";
        case GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT:
            return "GL_FRAMEBUFFER_INCOMPLETE_MISSING_ATTACHMENT";
        case GL_FRAMEBUFFER_INCOMPLETE_DRAW_BUFFER:
            return "GL_FRAMEBUFFER_INCOMPLETE_DRAW_BUFFER";
        case GL_FRAMEBUFFER_INCOMPLETE_READ_BUFFER:
            return "GL_FRAMEBUFFER_INCOMPLETE_READ_BUFFER";
        case GL_FRAMEBUFFER_UNSUPPORTED:
            return "GL_FRAMEBUFFER_UNSUPPORTED";
        case GL_FRAMEBUFFER_INCOMPLETE_MULTISAMPLE:
            return "GL_FRAMEBUFFER_INCOMPLETE_MULTISAMPLE";
        case GL_FRAMEBUFFER_INCOMPLETE_LAYER_TARGETS:
            return "GL_FRAMEBUFFER_INCOMPLETE_LAYER_TARGETS";
        default:
            return "unknown status";
    }
}

// Creates an immutable single-level texture; fails when the driver rejects the format.
Result<GlTexture> createTexture(GLenum format, int width, int height) {
    while (glGetError() != GL_NO_ERROR) {
        // Drop stale errors so the check below only sees ours.
    }
    GlTexture texture = createGlTexture(GL_TEXTURE_2D);
    glTextureStorage2D(texture.get(), 1, format, width, height);
    if (GLenum error = glGetError(); error != GL_NO_ERROR) {
        return Error{"Framebuffer: texture storage with internal format " + hex(format) +
                     " failed (GL error " + hex(error) + ")"};
    }
    // Nearest and clamped: attachments are read texel-exact by later passes.
    glTextureParameteri(texture.get(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(texture.get(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTextureParameteri(texture.get(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(texture.get(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return texture;
}

}  // namespace

Result<Framebuffer> Framebuffer::create(int width, int height,
                                        const std::vector<std::uint32_t>& colorFormats,
                                        bool withDepth) {
    if (width <= 0 || height <= 0) {
        return Error{"Framebuffer: invalid size " + std::to_string(width) + "x" +
                     std::to_string(height)};
    }
    GLint maxAttachments = 0;
    glGetIntegerv(GL_MAX_COLOR_ATTACHMENTS, &maxAttachments);
    if (static_cast<GLint>(colorFormats.size()) > maxAttachments) {
        return Error{"Framebuffer: " + std::to_string(colorFormats.size()) +
                     " colour attachments requested, the driver allows " +
                     std::to_string(maxAttachments)};
    }

    Framebuffer framebuffer;  // releases everything created so far on early return
    framebuffer.width_ = width;
    framebuffer.height_ = height;
    framebuffer.framebuffer_ = createGlFramebuffer();
    const GLuint id = framebuffer.framebuffer_.get();

    std::vector<GLenum> drawBuffers;
    for (std::size_t i = 0; i < colorFormats.size(); ++i) {
        Result<GlTexture> texture = createTexture(colorFormats[i], width, height);
        if (!texture) {
            return texture.error();
        }
        const GLenum attachment = GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(i);
        glNamedFramebufferTexture(id, attachment, texture->get(), 0);
        framebuffer.colorTextures_.push_back(std::move(texture.value()));
        framebuffer.colorFormats_.push_back(colorFormats[i]);
        drawBuffers.push_back(attachment);
    }
    if (withDepth) {
        Result<GlTexture> texture = createTexture(GL_DEPTH_COMPONENT32F, width, height);
        if (!texture) {
            return texture.error();
        }
        glNamedFramebufferTexture(id, GL_DEPTH_ATTACHMENT, texture->get(), 0);
        framebuffer.depthTexture_ = std::move(texture.value());
    }
    if (drawBuffers.empty()) {
        glNamedFramebufferDrawBuffer(id, GL_NONE);
        glNamedFramebufferReadBuffer(id, GL_NONE);
    } else {
        glNamedFramebufferDrawBuffers(id, static_cast<GLsizei>(drawBuffers.size()),
                                      drawBuffers.data());
    }
    const GLenum status = glCheckNamedFramebufferStatus(id, GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
        return Error{std::string("Framebuffer: incomplete (") + statusName(status) + ", " +
                     hex(status) + ")"};
    }
    return framebuffer;
}

Framebuffer::Framebuffer(Framebuffer&& other) noexcept {
    *this = std::move(other);
}

Framebuffer& Framebuffer::operator=(Framebuffer&& other) noexcept {
    if (this != &other) {
        // The handles delete what this framebuffer owned; the source is left empty.
        framebuffer_ = std::move(other.framebuffer_);
        colorTextures_ = std::exchange(other.colorTextures_, {});
        colorFormats_ = std::exchange(other.colorFormats_, {});
        depthTexture_ = std::move(other.depthTexture_);
        width_ = std::exchange(other.width_, 0);
        height_ = std::exchange(other.height_, 0);
    }
    return *this;
}

void Framebuffer::bind() const {
    SYLVA_CHECK(framebuffer_);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.get());
    glViewport(0, 0, width_, height_);
}

void Framebuffer::unbind() {
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void Framebuffer::clearColor(int attachment, const glm::vec4& color) const {
    SYLVA_CHECK(attachment >= 0 && attachment < colorCount());
    const float values[4] = {color.r, color.g, color.b, color.a};
    glClearNamedFramebufferfv(framebuffer_.get(), GL_COLOR, attachment, values);
}

void Framebuffer::clearDepth(float depth) const {
    SYLVA_CHECK(depthTexture_);
    glClearNamedFramebufferfv(framebuffer_.get(), GL_DEPTH, 0, &depth);
}

std::uint32_t Framebuffer::colorFormat(int index) const {
    SYLVA_CHECK(index >= 0 && index < colorCount());
    return colorFormats_[static_cast<std::size_t>(index)];
}

std::uint32_t Framebuffer::colorTexture(int index) const {
    SYLVA_CHECK(index >= 0 && index < colorCount());
    return colorTextures_[static_cast<std::size_t>(index)].get();
}

void Framebuffer::readInto(int attachment, std::uint32_t format, std::uint32_t type,
                           int bytesPerPixel, void* out) const {
    SYLVA_CHECK(framebuffer_);
    GLint previousRead = 0;
    GLint previousAlignment = 0;
    glGetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &previousRead);
    glGetIntegerv(GL_PACK_ALIGNMENT, &previousAlignment);

    if (attachment >= 0) {
        glNamedFramebufferReadBuffer(framebuffer_.get(),
                                     GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(attachment));
    }
    glBindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer_.get());
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width_, height_, format, type, out);
    glPixelStorei(GL_PACK_ALIGNMENT, previousAlignment);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(previousRead));

    // GL returns the bottom row first; images are stored top row first.
    const std::size_t rowBytes = static_cast<std::size_t>(width_) * bytesPerPixel;
    std::vector<std::uint8_t> row(rowBytes);
    auto* bytes = static_cast<std::uint8_t*>(out);
    for (int top = 0, bottom = height_ - 1; top < bottom; ++top, --bottom) {
        std::uint8_t* a = bytes + static_cast<std::size_t>(top) * rowBytes;
        std::uint8_t* b = bytes + static_cast<std::size_t>(bottom) * rowBytes;
        std::memcpy(row.data(), a, rowBytes);
        std::memcpy(a, b, rowBytes);
        std::memcpy(b, row.data(), rowBytes);
    }
}

std::vector<std::uint8_t> Framebuffer::readPixelsRGBA8(int attachment) const {
    SYLVA_CHECK(attachment >= 0 && attachment < colorCount());
    std::vector<std::uint8_t> pixels(static_cast<std::size_t>(width_) * height_ * 4);
    readInto(attachment, GL_RGBA, GL_UNSIGNED_BYTE, 4, pixels.data());
    return pixels;
}

std::vector<float> Framebuffer::readPixelsFloat(int attachment, int channels) const {
    SYLVA_CHECK(attachment >= 0 && attachment < colorCount());
    SYLVA_CHECK(channels >= 1 && channels <= 4);
    static constexpr GLenum kFormats[] = {GL_RED, GL_RG, GL_RGB, GL_RGBA};
    std::vector<float> pixels(static_cast<std::size_t>(width_) * height_ * channels);
    readInto(attachment, kFormats[channels - 1], GL_FLOAT,
             channels * static_cast<int>(sizeof(float)), pixels.data());
    return pixels;
}

std::vector<float> Framebuffer::readDepth() const {
    SYLVA_CHECK(depthTexture_);
    std::vector<float> depth(static_cast<std::size_t>(width_) * height_);
    readInto(-1, GL_DEPTH_COMPONENT, GL_FLOAT, static_cast<int>(sizeof(float)), depth.data());
    return depth;
}

}  // namespace sylva::render
