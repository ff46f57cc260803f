// GlfwContext: a GL 4.5 core context with a GLFW window (X11/GLX; needs DISPLAY, e.g. an
// Xvfb server). Private to sylva_render; use GlContext::create().
//
// Ownership: owns its GLFWwindow. GLFW itself is initialized with the first GlfwContext
// and terminated with the last one.
#pragma once

#include <memory>

#include "sylva/render/gl/GlContext.h"

namespace sylva::render {

class GlfwContext final : public GlContext {
public:
    // Fails with the reason only (the caller adds the back end name), e.g. "no display
    // (DISPLAY is not set); use --gl egl or osmesa for headless rendering".
    static Result<std::unique_ptr<GlContext>> create(const ContextOptions& options);

    ~GlfwContext() override;

    GlBackend backend() const override { return GlBackend::Glfw; }
    void makeCurrent() override;
    void swapBuffers() override;
    void pollEvents() override;
    void waitEvents(double seconds) override;
    void framebufferSize(int& width, int& height) const override;
    bool shouldClose() const override;
    void* nativeWindow() const override { return window_; }

private:
    GlfwContext() = default;

    void* window_ = nullptr;  // GLFWwindow
    bool ownsGlfwInit_ = false;
};

}  // namespace sylva::render
