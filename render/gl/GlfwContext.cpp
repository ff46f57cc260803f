#include "GlfwContext.h"

// GLFW_INCLUDE_NONE: GL declarations come from glad only, never from GLFW's GL/gl.h.
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <cstdlib>
#include <mutex>
#include <string>

namespace sylva::render {
namespace {

std::mutex gGlfwMutex;
int gGlfwUsers = 0;
// GLFW reports details only through its error callback; keep the last one for messages.
thread_local std::string gLastGlfwError;

void onGlfwError(int /*code*/, const char* description) {
    gLastGlfwError = description != nullptr ? description : "unknown GLFW error";
}

Error glfwFailure(const char* what) {
    std::string message = std::string(what) + " failed";
    if (!gLastGlfwError.empty()) {
        message += ": " + gLastGlfwError;
    }
    return Error{message};
}

}  // namespace

Result<std::unique_ptr<GlContext>> GlfwContext::create(const ContextOptions& options) {
    const char* display = std::getenv("DISPLAY");
    // Debian's GLFW 3.3 is built for X11 only, so DISPLAY is the one thing that matters.
    if (display == nullptr || display[0] == '\0') {
        return Error{
            "no display (DISPLAY is not set); use --gl egl or osmesa for headless rendering"};
    }
    if (options.width <= 0 || options.height <= 0) {
        return Error{"invalid window size " + std::to_string(options.width) + "x" +
                     std::to_string(options.height)};
    }

    std::unique_ptr<GlfwContext> context(new GlfwContext());
    {
        std::lock_guard lock(gGlfwMutex);
        gLastGlfwError.clear();
        glfwSetErrorCallback(onGlfwError);
        if (gGlfwUsers == 0 && !glfwInit()) {
            return glfwFailure("glfwInit");
        }
        ++gGlfwUsers;
        context->ownsGlfwInit_ = true;
    }

    glfwDefaultWindowHints();
    glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
    glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
    glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
    glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
    glfwWindowHint(GLFW_VISIBLE, options.visible ? GLFW_TRUE : GLFW_FALSE);
    GLFWwindow* window =
        glfwCreateWindow(options.width, options.height, options.title.c_str(), nullptr, nullptr);
    if (window == nullptr) {
        return glfwFailure("glfwCreateWindow(4.5 core)");
    }
    context->window_ = window;
    glfwMakeContextCurrent(window);
    if (Status loaded = context->loadGl(reinterpret_cast<GlProcLoader>(glfwGetProcAddress));
        !loaded) {
        return loaded.error();
    }
    return std::unique_ptr<GlContext>(std::move(context));
}

GlfwContext::~GlfwContext() {
    forgetLoadedGl();
    auto* window = static_cast<GLFWwindow*>(window_);
    if (window != nullptr) {
        if (glfwGetCurrentContext() == window) {
            glfwMakeContextCurrent(nullptr);
        }
        glfwDestroyWindow(window);
    }
    if (ownsGlfwInit_) {
        std::lock_guard lock(gGlfwMutex);
        if (--gGlfwUsers == 0) {
            glfwTerminate();
        }
    }
}

void GlfwContext::makeCurrent() {
    glfwMakeContextCurrent(static_cast<GLFWwindow*>(window_));
    reloadGlIfNeeded(reinterpret_cast<GlProcLoader>(glfwGetProcAddress));
}

void GlfwContext::swapBuffers() {
    glfwSwapBuffers(static_cast<GLFWwindow*>(window_));
}

void GlfwContext::pollEvents() {
    glfwPollEvents();
}

void GlfwContext::waitEvents(double seconds) {
    glfwWaitEventsTimeout(seconds);
}

void GlfwContext::framebufferSize(int& width, int& height) const {
    glfwGetFramebufferSize(static_cast<GLFWwindow*>(window_), &width, &height);
}

bool GlfwContext::shouldClose() const {
    return glfwWindowShouldClose(static_cast<GLFWwindow*>(window_)) != 0;
}

}  // namespace sylva::render
