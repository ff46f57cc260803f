#include "WindowBlit.h"

#include <glad/gl.h>

namespace sylva::render {

void WindowBlit::show(const RgbaImage& image, int windowWidth, int windowHeight) {
    if (image.width <= 0 || image.height <= 0 || windowWidth <= 0 || windowHeight <= 0) {
        return;
    }
    if (!texture_ || width_ != image.width || height_ != image.height) {
        texture_ = createGlTexture(GL_TEXTURE_2D);
        glTextureStorage2D(texture_.get(), 1, GL_RGBA8, image.width, image.height);
        framebuffer_ = createGlFramebuffer();
        glNamedFramebufferTexture(framebuffer_.get(), GL_COLOR_ATTACHMENT0, texture_.get(), 0);
        width_ = image.width;
        height_ = image.height;
    }
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTextureSubImage2D(texture_.get(), 0, 0, 0, image.width, image.height, GL_RGBA,
                        GL_UNSIGNED_BYTE, image.pixels.data());
    glDisable(GL_FRAMEBUFFER_SRGB);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    glViewport(0, 0, windowWidth, windowHeight);
    // Row 0 of the image is the top: blit with the destination's y range reversed.
    glBlitNamedFramebuffer(
        framebuffer_.get(), 0, 0, 0, image.width, image.height, 0, windowHeight, windowWidth, 0,
        GL_COLOR_BUFFER_BIT,
        image.width == windowWidth && image.height == windowHeight ? GL_NEAREST : GL_LINEAR);
}

}  // namespace sylva::render
