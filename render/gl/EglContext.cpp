#include "EglContext.h"

// EGL headers stay in this file: they pull in platform headers and GL typedefs that clash
// with glad's when mixed in one translation unit.
#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstdio>
#include <cstring>
#include <mutex>
#include <string>

namespace sylva::render {
namespace {

std::mutex gDisplayMutex;
int gDisplayUsers = 0;

std::string eglErrorName(EGLint code) {
    switch (code) {
        case EGL_SUCCESS:
            return "EGL_SUCCESS";
        case EGL_NOT_INITIALIZED:
            return "EGL_NOT_INITIALIZED";
        case EGL_BAD_ACCESS:
            return "EGL_BAD_ACCESS";
        case EGL_BAD_ALLOC:
            return "EGL_BAD_ALLOC";
        case EGL_BAD_ATTRIBUTE:
            return "EGL_BAD_ATTRIBUTE";
        case EGL_BAD_CONFIG:
            return "EGL_BAD_CONFIG";
        case EGL_BAD_CONTEXT:
            return "EGL_BAD_CONTEXT";
        case EGL_BAD_CURRENT_SURFACE:
            return "EGL_BAD_CURRENT_SURFACE";
        case EGL_BAD_DISPLAY:
            return "EGL_BAD_DISPLAY";
        case EGL_BAD_MATCH:
            return "EGL_BAD_MATCH";
        case EGL_BAD_NATIVE_PIXMAP:
            return "EGL_BAD_NATIVE_PIXMAP";
        case EGL_BAD_NATIVE_WINDOW:
            return "EGL_BAD_NATIVE_WINDOW";
        case EGL_BAD_PARAMETER:
            return "EGL_BAD_PARAMETER";
        case EGL_BAD_SURFACE:
            return "EGL_BAD_SURFACE";
        case EGL_CONTEXT_LOST:
            return "EGL_CONTEXT_LOST";
        default: {
            char buffer[32];
            std::snprintf(buffer, sizeof buffer, "0x%04x", static_cast<unsigned>(code));
            return buffer;
        }
    }
}

Error eglFailure(const char* what) {
    return Error{std::string(what) + " failed: " + eglErrorName(eglGetError())};
}

bool hasExtension(const char* list, const char* name) {
    if (list == nullptr) {
        return false;
    }
    const std::size_t length = std::strlen(name);
    for (const char* p = std::strstr(list, name); p != nullptr; p = std::strstr(p + 1, name)) {
        const bool startOk = p == list || p[-1] == ' ';
        const bool endOk = p[length] == ' ' || p[length] == '\0';
        if (startOk && endOk) {
            return true;
        }
    }
    return false;
}

// Initializes (or re-uses) the process-wide surfaceless display.
Result<EGLDisplay> acquireDisplay() {
    const char* clientExtensions = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    if (!hasExtension(clientExtensions, "EGL_MESA_platform_surfaceless")) {
        return Error{"the EGL client does not support EGL_MESA_platform_surfaceless"};
    }
    auto getPlatformDisplay = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
        eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (getPlatformDisplay == nullptr) {
        return Error{"eglGetPlatformDisplayEXT is not available"};
    }
    EGLDisplay display =
        getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (display == EGL_NO_DISPLAY) {
        return eglFailure("eglGetPlatformDisplayEXT");
    }
    std::lock_guard lock(gDisplayMutex);
    if (gDisplayUsers == 0) {
        EGLint major = 0;
        EGLint minor = 0;
        if (!eglInitialize(display, &major, &minor)) {
            return eglFailure("eglInitialize");
        }
    }
    ++gDisplayUsers;
    return display;
}

void releaseDisplay(EGLDisplay display) {
    std::lock_guard lock(gDisplayMutex);
    if (--gDisplayUsers == 0) {
        eglTerminate(display);
    }
}

}  // namespace

Result<std::unique_ptr<GlContext>> EglContext::create(const ContextOptions& /*options*/) {
    Result<EGLDisplay> display = acquireDisplay();
    if (!display) {
        return display.error();
    }
    // From here on the destructor cleans up whatever was created.
    std::unique_ptr<EglContext> context(new EglContext());
    context->display_ = *display;

    if (!eglBindAPI(EGL_OPENGL_API)) {
        return eglFailure("eglBindAPI(EGL_OPENGL_API)");
    }
    const EGLint configAttributes[] = {EGL_SURFACE_TYPE,
                                       EGL_PBUFFER_BIT,
                                       EGL_RED_SIZE,
                                       8,
                                       EGL_GREEN_SIZE,
                                       8,
                                       EGL_BLUE_SIZE,
                                       8,
                                       EGL_ALPHA_SIZE,
                                       8,
                                       EGL_DEPTH_SIZE,
                                       24,
                                       EGL_RENDERABLE_TYPE,
                                       EGL_OPENGL_BIT,
                                       EGL_NONE};
    EGLConfig config = nullptr;
    EGLint configCount = 0;
    if (!eglChooseConfig(*display, configAttributes, &config, 1, &configCount)) {
        return eglFailure("eglChooseConfig");
    }
    if (configCount == 0) {
        return Error{"eglChooseConfig found no RGBA8 + depth24 OpenGL config"};
    }
    const EGLint contextAttributes[] = {EGL_CONTEXT_MAJOR_VERSION,
                                        4,
                                        EGL_CONTEXT_MINOR_VERSION,
                                        5,
                                        EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                        EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                        EGL_NONE};
    context->context_ = eglCreateContext(*display, config, EGL_NO_CONTEXT, contextAttributes);
    if (context->context_ == EGL_NO_CONTEXT) {
        context->context_ = nullptr;
        return eglFailure("eglCreateContext(4.5 core)");
    }
    if (!eglMakeCurrent(*display, EGL_NO_SURFACE, EGL_NO_SURFACE, context->context_)) {
        return eglFailure("eglMakeCurrent(surfaceless)");
    }
    if (Status loaded = context->loadGl(reinterpret_cast<GlProcLoader>(eglGetProcAddress));
        !loaded) {
        return loaded.error();
    }
    return std::unique_ptr<GlContext>(std::move(context));
}

EglContext::~EglContext() {
    forgetLoadedGl();
    if (context_ != nullptr) {
        if (eglGetCurrentContext() == context_) {
            eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        }
        eglDestroyContext(display_, context_);
    }
    if (display_ != nullptr) {
        releaseDisplay(display_);
    }
}

void EglContext::makeCurrent() {
    // Always bind: another back end may have made its own context current on this thread
    // without EGL knowing.
    SYLVA_CHECK_MESSAGE(eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, context_),
                        "eglMakeCurrent failed for an existing context");
    reloadGlIfNeeded(reinterpret_cast<GlProcLoader>(eglGetProcAddress));
}

}  // namespace sylva::render
