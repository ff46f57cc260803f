#include "sylva/render/gl/GlContext.h"

#include <glad/gl.h>

#include <cstdio>
#include <cstdlib>

#include "EglContext.h"
#include "GlfwContext.h"
#include "OsMesaContext.h"
#include "sylva/render/gl/GlRequirements.h"

namespace sylva::render {
namespace {

// The context glad's global function pointers were last loaded for. Contexts of different
// back ends live in different driver libraries, so their entry points must not be mixed.
const GlContext* gLoadedFor = nullptr;

const char* backendLabel(GlBackend backend) {
    switch (backend) {
        case GlBackend::Egl:
            return "EGL surfaceless";
        case GlBackend::OsMesa:
            return "OSMesa";
        case GlBackend::Glfw:
            return "GLFW";
    }
    return "?";
}

Result<std::unique_ptr<GlContext>> createBackend(GlBackend backend, const ContextOptions& options) {
    switch (backend) {
        case GlBackend::Egl:
            return EglContext::create(options);
        case GlBackend::OsMesa:
            return OsMesaContext::create(options);
        case GlBackend::Glfw:
            return GlfwContext::create(options);
    }
    return Error{"invalid GlBackend value"};
}

#ifndef NDEBUG
void GLAPIENTRY debugCallback(GLenum source, GLenum type, GLuint /*id*/, GLenum severity,
                              GLsizei /*length*/, const GLchar* message, const void* /*user*/) {
    // Only API errors: shader compile failures reach the caller through Result (with file
    // names), and llvmpipe's performance notes would drown everything else.
    if (type == GL_DEBUG_TYPE_ERROR && severity == GL_DEBUG_SEVERITY_HIGH &&
        source != GL_DEBUG_SOURCE_SHADER_COMPILER) {
        std::fprintf(stderr, "GL error: %s\n", message);
    }
}
#endif

}  // namespace

const char* backendName(GlBackend backend) {
    switch (backend) {
        case GlBackend::Egl:
            return "egl";
        case GlBackend::OsMesa:
            return "osmesa";
        case GlBackend::Glfw:
            return "glfw";
    }
    return "?";
}

Result<GlBackend> parseBackend(std::string_view text) {
    for (GlBackend backend : {GlBackend::Egl, GlBackend::OsMesa, GlBackend::Glfw}) {
        if (text == backendName(backend)) {
            return backend;
        }
    }
    return Error{"unknown GL back end '" + std::string(text) + "' (expected egl, osmesa or glfw)"};
}

Result<std::unique_ptr<GlContext>> GlContext::create(const ContextOptions& options) {
    std::optional<GlBackend> backend = options.backend;
    if (!backend) {
        const char* env = std::getenv("SYLVA_GL");
        if (env != nullptr && env[0] != '\0') {
            Result<GlBackend> parsed = parseBackend(env);
            if (!parsed) {
                return Error{"SYLVA_GL: " + parsed.error().message};
            }
            backend = *parsed;
        }
    }

    if (backend) {
        Result<std::unique_ptr<GlContext>> context = createBackend(*backend, options);
        if (!context) {
            return Error{std::string(backendLabel(*backend)) + ": " + context.error().message};
        }
        return context;
    }

    std::string tried;
    for (GlBackend candidate : {GlBackend::Egl, GlBackend::OsMesa}) {
        Result<std::unique_ptr<GlContext>> context = createBackend(candidate, options);
        if (context) {
            return context;
        }
        if (!tried.empty()) {
            tried += ", ";
        }
        tried += std::string(backendLabel(candidate)) + " (" + context.error().message + ")";
    }
    return Error{"no OpenGL 4.5 core context could be created; tried: " + tried};
}

GlContext::~GlContext() = default;

void GlContext::swapBuffers() {}
void GlContext::pollEvents() {}
void GlContext::waitEvents(double /*seconds*/) {}
void GlContext::framebufferSize(int& width, int& height) const {
    width = 0;
    height = 0;
}
bool GlContext::shouldClose() const {
    return false;
}
void* GlContext::nativeWindow() const {
    return nullptr;
}

Status GlContext::loadGl(GlProcLoader loader) {
    gLoadedFor = nullptr;
    const int version = gladLoadGL(reinterpret_cast<GLADloadfunc>(loader));
    if (version == 0) {
        return Error{"loading GL functions failed (gladLoadGL returned 0)"};
    }
    const int major = GLAD_VERSION_MAJOR(version);
    const int minor = GLAD_VERSION_MINOR(version);
    GLint profile = 0;
    glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
    const bool core = (profile & GL_CONTEXT_CORE_PROFILE_BIT) != 0;
    if (major * 10 + minor < 45 || !core) {
        return Error{"got OpenGL " + std::to_string(major) + "." + std::to_string(minor) +
                     (core ? " core" : " compatibility") + ", need 4.5 core"};
    }
    if (Status features = checkGlFeatures(queryGlFeatures()); !features) {
        return features.error();
    }
    gLoadedFor = this;
    glVersion_ = major * 10 + minor;

    const auto* rendererString = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
    const auto* versionString = reinterpret_cast<const char*>(glGetString(GL_VERSION));
    renderer_ = std::string(rendererString ? rendererString : "?") + ", " +
                (versionString ? versionString : "?");

#ifndef NDEBUG
    // Debug output is core since 4.3; the extension check covers odd drivers.
    if (GLAD_GL_KHR_debug || glVersion_ >= 43) {
        glEnable(GL_DEBUG_OUTPUT);
        glDebugMessageCallback(debugCallback, nullptr);
    }
#endif
    return Status::success();
}

void GlContext::reloadGlIfNeeded(GlProcLoader loader) {
    if (gLoadedFor == this) {
        return;
    }
    // Another context (possibly another driver library) was loaded last. gladLoadGL cannot
    // fail here because it already succeeded once for this context.
    SYLVA_CHECK(gladLoadGL(reinterpret_cast<GLADloadfunc>(loader)) != 0);
    gLoadedFor = this;
}

void GlContext::forgetLoadedGl() {
    if (gLoadedFor == this) {
        gLoadedFor = nullptr;
    }
}

}  // namespace sylva::render
