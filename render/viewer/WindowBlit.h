// WindowBlit: shows a rendered frame in the window: the RGBA8 pixels (already sRGB
// encoded, so the default framebuffer's sRGB conversion stays off) are uploaded into a
// texture and copied to the default framebuffer with glBlitNamedFramebuffer, flipped
// (images are stored top row first) and scaled to the window with linear filtering.
// No shader is involved. Private to render/viewer.
//
// Needs the window's GL context current; owns its texture and read framebuffer.
#pragma once

#include "sylva/core/image/Image.h"
#include "sylva/render/gl/GlHandle.h"

namespace sylva::render {

class WindowBlit {
public:
    // Draws `image` over the whole default framebuffer of `windowWidth` × `windowHeight`
    // pixels (the caller swaps buffers).
    void show(const RgbaImage& image, int windowWidth, int windowHeight);

private:
    GlTexture texture_;
    GlFramebuffer framebuffer_;
    int width_ = 0;
    int height_ = 0;
};

}  // namespace sylva::render
