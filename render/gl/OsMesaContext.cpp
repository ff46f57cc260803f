#include "OsMesaContext.h"

// osmesa.h includes GL/gl.h, whose declarations clash with glad's: keep it in this file.
#include <GL/osmesa.h>

#include <string>

namespace sylva::render {

Result<std::unique_ptr<GlContext>> OsMesaContext::create(const ContextOptions& options) {
    if (options.width <= 0 || options.height <= 0) {
        return Error{"invalid buffer size " + std::to_string(options.width) + "x" +
                     std::to_string(options.height)};
    }
    // Ask for exactly 4.5: Mesa 22 refuses 4.6, and anything older is useless to us.
    const int attributes[] = {OSMESA_FORMAT,
                              OSMESA_RGBA,
                              OSMESA_DEPTH_BITS,
                              24,
                              OSMESA_STENCIL_BITS,
                              8,
                              OSMESA_PROFILE,
                              OSMESA_CORE_PROFILE,
                              OSMESA_CONTEXT_MAJOR_VERSION,
                              4,
                              OSMESA_CONTEXT_MINOR_VERSION,
                              5,
                              0};
    OSMesaContext handle = OSMesaCreateContextAttribs(attributes, nullptr);
    if (handle == nullptr) {
        return Error{"OSMesaCreateContextAttribs(4.5 core) failed"};
    }
    std::unique_ptr<OsMesaContext> context(new OsMesaContext());
    context->context_ = handle;
    context->width_ = options.width;
    context->height_ = options.height;
    context->buffer_.resize(static_cast<std::size_t>(options.width) *
                            static_cast<std::size_t>(options.height) * 4);
    if (!OSMesaMakeCurrent(handle, context->buffer_.data(), GL_UNSIGNED_BYTE, options.width,
                           options.height)) {
        return Error{"OSMesaMakeCurrent failed"};
    }
    // Rows bottom-up, as glReadPixels returns them everywhere else.
    OSMesaPixelStore(OSMESA_Y_UP, 1);
    if (Status loaded = context->loadGl(reinterpret_cast<GlProcLoader>(OSMesaGetProcAddress));
        !loaded) {
        return loaded.error();
    }
    return std::unique_ptr<GlContext>(std::move(context));
}

OsMesaContext::~OsMesaContext() {
    forgetLoadedGl();
    if (context_ != nullptr) {
        auto* handle = static_cast<OSMesaContext>(context_);
        if (OSMesaGetCurrentContext() == handle) {
            // A null context and buffer releases the current context.
            OSMesaMakeCurrent(nullptr, nullptr, 0, 0, 0);
        }
        OSMesaDestroyContext(handle);
    }
}

void OsMesaContext::makeCurrent() {
    SYLVA_CHECK_MESSAGE(OSMesaMakeCurrent(static_cast<OSMesaContext>(context_), buffer_.data(),
                                          GL_UNSIGNED_BYTE, width_, height_),
                        "OSMesaMakeCurrent failed for an existing context");
    reloadGlIfNeeded(reinterpret_cast<GlProcLoader>(OSMesaGetProcAddress));
}

}  // namespace sylva::render
