// GlContext: an OpenGL 4.5 core context made current on the calling thread, created
// through one of three back ends: EGL surfaceless (headless, default), OSMesa (headless,
// fallback) or GLFW (a window, needs an X display).
//
// Ownership: create() returns a unique_ptr; the context, its display connection or window
// and (for OSMesa) its colour buffer live exactly as long as that object. Destroying it
// releases the context if it is current. Contexts may be created and destroyed any number
// of times in one process.
//
// GL functions are loaded through glad (global function pointers). After create() the new
// context is current and glad is loaded for it; makeCurrent() reloads glad when switching
// between contexts of different back ends, so every GL call goes to the right driver.
//
// Failures never throw: create() returns an Error whose message names every back end tried
// and why each failed.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "sylva/core/base/Result.h"

namespace sylva::render {

enum class GlBackend { Egl, OsMesa, Glfw };

// "egl", "osmesa" or "glfw".
const char* backendName(GlBackend backend);

// Parses "egl", "osmesa" or "glfw" (exact, lower case). Fails with
// "unknown GL back end 'x' (expected egl, osmesa or glfw)".
Result<GlBackend> parseBackend(std::string_view text);

struct ContextOptions {
    // nullopt: the SYLVA_GL environment variable if set and not empty (a bad value is an
    // error), else EGL surfaceless with OSMesa as the fallback. An explicit back end is the
    // only one tried.
    std::optional<GlBackend> backend;
    int width = 64;  // OSMesa default framebuffer / GLFW window size in pixels
    int height = 64;
    bool visible = false;  // GLFW: show the window
    std::string title = "Sylva";
};

class GlContext {
public:
    // Creates a 4.5 core context, makes it current and loads glad. Fails when no back end
    // could provide GL >= 4.5 core; the message lists each back end tried and its error.
    static Result<std::unique_ptr<GlContext>> create(const ContextOptions& options = {});

    virtual ~GlContext();
    GlContext(const GlContext&) = delete;
    GlContext& operator=(const GlContext&) = delete;

    virtual GlBackend backend() const = 0;

    // Makes this context current on the calling thread (and reloads glad if another
    // context's driver was loaded last). Aborts if the driver refuses, which only happens
    // when the context was lost.
    virtual void makeCurrent() = 0;

    // "GL_RENDERER, GL_VERSION" as reported when the context was created, e.g.
    // "llvmpipe (LLVM 15.0.6, 256 bits), 4.5 (Core Profile) Mesa 22.3.6".
    std::string renderer() const { return renderer_; }

    // GL version of the context as major * 10 + minor (45 for 4.5).
    int glVersion() const { return glVersion_; }

    // Window operations: GLFW only. Other back ends: no-op / false / nullptr.
    virtual void swapBuffers();
    virtual void pollEvents();
    // Sleeps until an input event arrives or `seconds` pass, then handles the events.
    virtual void waitEvents(double seconds);
    // The window's framebuffer size in pixels (GLFW); 0 x 0 for the headless back ends.
    virtual void framebufferSize(int& width, int& height) const;
    virtual bool shouldClose() const;
    virtual void* nativeWindow() const;  // GLFWwindow* for GLFW

protected:
    GlContext() = default;

    using GlProc = void (*)();
    using GlProcLoader = GlProc (*)(const char* name);

    // For back ends, with the new context current: loads glad through `loader`, checks
    // for GL >= 4.5 core, records renderer() and (in debug builds) enables KHR_debug
    // output. Fails with a reason such as "got OpenGL 3.3, need 4.5 core".
    Status loadGl(GlProcLoader loader);

    // For makeCurrent() overrides: reloads glad if it was last loaded for another context.
    void reloadGlIfNeeded(GlProcLoader loader);

    // For destructors: forgets that glad was loaded for this context.
    void forgetLoadedGl();

private:
    std::string renderer_;
    int glVersion_ = 0;
};

}  // namespace sylva::render
