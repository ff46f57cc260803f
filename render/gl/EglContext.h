// EglContext: a GL 4.5 core context on the EGL surfaceless platform (Mesa), with no
// window and no default framebuffer: render into FBOs. Private to sylva_render; use
// GlContext::create().
//
// Ownership: owns its EGLContext. The EGLDisplay is shared by all EglContexts of the
// process (EGL returns the same handle for the same platform) and reference counted, so it
// is terminated when the last EglContext is destroyed.
#pragma once

#include <memory>

#include "sylva/render/gl/GlContext.h"

namespace sylva::render {

class EglContext final : public GlContext {
public:
    // Fails with the reason only (the caller adds the back end name), e.g.
    // "eglInitialize failed: EGL_NOT_INITIALIZED".
    static Result<std::unique_ptr<GlContext>> create(const ContextOptions& options);

    ~EglContext() override;

    GlBackend backend() const override { return GlBackend::Egl; }
    void makeCurrent() override;

private:
    EglContext() = default;

    void* display_ = nullptr;  // EGLDisplay
    void* context_ = nullptr;  // EGLContext
};

}  // namespace sylva::render
