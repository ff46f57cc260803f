// GlContext and Framebuffer on Mesa llvmpipe: EGL surfaceless and OSMesa always, GLFW only
// when an X display is available.
#include "sylva/render/gl/GlContext.h"

#include <glad/gl.h>

#include <gtest/gtest.h>

#include <cstdlib>
#include <optional>
#include <string>

#include "ScopedEnv.h"
#include "sylva/render/gl/Framebuffer.h"

namespace sylva::render {
namespace {

using test::ScopedEnv;

Result<std::unique_ptr<GlContext>> createContext(GlBackend backend) {
    ContextOptions options;
    options.backend = backend;
    return GlContext::create(options);
}

// Clears an RGBA8 FBO (top half green, bottom half orange through the scissor) and checks
// the read-back, including the top-to-bottom row order.
void expectClearAndReadBack() {
    constexpr int kWidth = 8;
    constexpr int kHeight = 6;
    Result<Framebuffer> framebuffer = Framebuffer::create(kWidth, kHeight, {GL_RGBA8}, true);
    ASSERT_TRUE(framebuffer.ok()) << framebuffer.error().message;
    framebuffer->bind();
    glClearColor(1.0f, 0.2f, 0.0f, 1.0f);
    glClearDepth(0.25);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    glEnable(GL_SCISSOR_TEST);
    glScissor(0, kHeight / 2, kWidth, kHeight / 2);  // GL y is bottom-up: the top half
    glClearColor(0.0f, 1.0f, 0.0f, 1.0f);
    glClear(GL_COLOR_BUFFER_BIT);
    glDisable(GL_SCISSOR_TEST);
    Framebuffer::unbind();
    EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));

    const std::vector<std::uint8_t> pixels = framebuffer->readPixelsRGBA8(0);
    ASSERT_EQ(pixels.size(), static_cast<std::size_t>(kWidth * kHeight * 4));
    for (int y = 0; y < kHeight; ++y) {
        for (int x = 0; x < kWidth; ++x) {
            const std::uint8_t* p = &pixels[static_cast<std::size_t>((y * kWidth + x) * 4)];
            if (y < kHeight / 2) {  // top rows come first
                EXPECT_EQ(p[0], 0);
                EXPECT_EQ(p[1], 255);
            } else {
                EXPECT_EQ(p[0], 255);
                EXPECT_EQ(p[1], 51);
            }
            EXPECT_EQ(p[2], 0);
            EXPECT_EQ(p[3], 255);
        }
    }
    for (float depth : framebuffer->readDepth()) {
        EXPECT_FLOAT_EQ(depth, 0.25f);
    }
}

TEST(GlBackendTest, ParsesNames) {
    for (GlBackend backend : {GlBackend::Egl, GlBackend::OsMesa, GlBackend::Glfw}) {
        Result<GlBackend> parsed = parseBackend(backendName(backend));
        ASSERT_TRUE(parsed.ok());
        EXPECT_EQ(*parsed, backend);
    }
    EXPECT_STREQ(backendName(GlBackend::Egl), "egl");
    EXPECT_STREQ(backendName(GlBackend::OsMesa), "osmesa");
    EXPECT_STREQ(backendName(GlBackend::Glfw), "glfw");
}

TEST(GlBackendTest, RejectsUnknownNames) {
    for (const char* text : {"bogus", "", "EGL", "osmesa "}) {
        Result<GlBackend> parsed = parseBackend(text);
        ASSERT_FALSE(parsed.ok()) << text;
        EXPECT_EQ(parsed.error().message,
                  "unknown GL back end '" + std::string(text) + "' (expected egl, osmesa or glfw)");
    }
}

TEST(GlContextTest, BadSylvaGlIsAnError) {
    ScopedEnv env("SYLVA_GL", "bogus");
    Result<std::unique_ptr<GlContext>> context = GlContext::create();
    ASSERT_FALSE(context.ok());
    EXPECT_EQ(context.error().message,
              "SYLVA_GL: unknown GL back end 'bogus' (expected egl, osmesa or glfw)");
}

TEST(GlContextTest, SylvaGlSelectsTheBackend) {
    ScopedEnv env("SYLVA_GL", "osmesa");
    Result<std::unique_ptr<GlContext>> context = GlContext::create();
    ASSERT_TRUE(context.ok()) << context.error().message;
    EXPECT_EQ((*context)->backend(), GlBackend::OsMesa);
}

TEST(GlContextTest, DefaultIsEgl) {
    ScopedEnv env("SYLVA_GL", nullptr);
    Result<std::unique_ptr<GlContext>> context = GlContext::create();
    ASSERT_TRUE(context.ok()) << context.error().message;
    EXPECT_EQ((*context)->backend(), GlBackend::Egl);
}

TEST(GlContextTest, GlfwWithoutDisplayExplainsWhy) {
    ScopedEnv env("DISPLAY", nullptr);
    Result<std::unique_ptr<GlContext>> context = createContext(GlBackend::Glfw);
    ASSERT_FALSE(context.ok());
    EXPECT_EQ(context.error().message,
              "GLFW: no display (DISPLAY is not set); use --gl egl or osmesa for headless "
              "rendering");
}

class HeadlessContextTest : public testing::TestWithParam<GlBackend> {};

TEST_P(HeadlessContextTest, Creates45CoreAndClearsAFramebuffer) {
    Result<std::unique_ptr<GlContext>> context = createContext(GetParam());
    ASSERT_TRUE(context.ok()) << context.error().message;
    GlContext& gl = **context;
    EXPECT_EQ(gl.backend(), GetParam());
    EXPECT_GE(gl.glVersion(), 45);
    EXPECT_NE(gl.renderer().find("Core Profile"), std::string::npos) << gl.renderer();
    EXPECT_FALSE(gl.shouldClose());
    EXPECT_EQ(gl.nativeWindow(), nullptr);
    gl.swapBuffers();  // a no-op without a window

    GLint major = 0;
    GLint minor = 0;
    GLint profile = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    glGetIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
    EXPECT_GE(major * 10 + minor, 45);
    EXPECT_TRUE(profile & GL_CONTEXT_CORE_PROFILE_BIT);
    expectClearAndReadBack();
}

TEST_P(HeadlessContextTest, CanBeCreatedAgainAfterDestruction) {
    for (int round = 0; round < 3; ++round) {
        Result<std::unique_ptr<GlContext>> context = createContext(GetParam());
        ASSERT_TRUE(context.ok()) << "round " << round << ": " << context.error().message;
        expectClearAndReadBack();
    }
}

TEST_P(HeadlessContextTest, FloatAttachmentsAndClearHelpers) {
    Result<std::unique_ptr<GlContext>> context = createContext(GetParam());
    ASSERT_TRUE(context.ok()) << context.error().message;
    Result<Framebuffer> framebuffer =
        Framebuffer::create(4, 3, {GL_RGBA8, GL_RGBA32F, GL_R32F}, true);
    ASSERT_TRUE(framebuffer.ok()) << framebuffer.error().message;
    EXPECT_EQ(framebuffer->colorCount(), 3);
    EXPECT_NE(framebuffer->colorTexture(1), 0u);
    EXPECT_NE(framebuffer->depthTexture(), 0u);
    framebuffer->clearColor(1, {-2.0f, 0.5f, 1000.0f, 3.0f});
    framebuffer->clearColor(2, {7.25f, 0.0f, 0.0f, 0.0f});
    framebuffer->clearDepth(0.75f);
    const std::vector<float> rgba = framebuffer->readPixelsFloat(1, 4);
    ASSERT_EQ(rgba.size(), 4u * 3u * 4u);
    for (std::size_t i = 0; i < rgba.size(); i += 4) {
        EXPECT_EQ(rgba[i], -2.0f);
        EXPECT_EQ(rgba[i + 1], 0.5f);
        EXPECT_EQ(rgba[i + 2], 1000.0f);
        EXPECT_EQ(rgba[i + 3], 3.0f);
    }
    for (float value : framebuffer->readPixelsFloat(2, 1)) {
        EXPECT_EQ(value, 7.25f);
    }
    for (float value : framebuffer->readDepth()) {
        EXPECT_EQ(value, 0.75f);
    }

    Framebuffer moved = std::move(*framebuffer);
    EXPECT_EQ(framebuffer->id(), 0u);
    EXPECT_NE(moved.id(), 0u);
}

TEST_P(HeadlessContextTest, FramebufferErrorsAreResults) {
    Result<std::unique_ptr<GlContext>> context = createContext(GetParam());
    ASSERT_TRUE(context.ok()) << context.error().message;
    Result<Framebuffer> badSize = Framebuffer::create(0, 4, {GL_RGBA8}, false);
    ASSERT_FALSE(badSize.ok());
    EXPECT_EQ(badSize.error().message, "Framebuffer: invalid size 0x4");
    Result<Framebuffer> badFormat = Framebuffer::create(4, 4, {0x1234}, false);
    ASSERT_FALSE(badFormat.ok());
    EXPECT_NE(badFormat.error().message.find("internal format 0x1234"), std::string::npos)
        << badFormat.error().message;
    // RGB9_E5 is a valid texture format but not colour-renderable.
    Result<Framebuffer> incomplete = Framebuffer::create(4, 4, {GL_RGB9_E5}, false);
    ASSERT_FALSE(incomplete.ok());
    EXPECT_NE(incomplete.error().message.find("Framebuffer: incomplete"), std::string::npos)
        << incomplete.error().message;
}

INSTANTIATE_TEST_SUITE_P(Backends, HeadlessContextTest,
                         testing::Values(GlBackend::Egl, GlBackend::OsMesa),
                         [](const testing::TestParamInfo<GlBackend>& param) {
                             return std::string(backendName(param.param));
                         });

TEST(GlContextTest, EglAndOsMesaCanBeAliveTogether) {
    Result<std::unique_ptr<GlContext>> egl = createContext(GlBackend::Egl);
    ASSERT_TRUE(egl.ok()) << egl.error().message;
    Result<std::unique_ptr<GlContext>> osmesa = createContext(GlBackend::OsMesa);
    ASSERT_TRUE(osmesa.ok()) << osmesa.error().message;
    for (int round = 0; round < 2; ++round) {
        (*egl)->makeCurrent();
        expectClearAndReadBack();
        (*osmesa)->makeCurrent();
        expectClearAndReadBack();
    }
}

TEST(GlContextTest, GlfwWindowWhenADisplayExists) {
    const char* display = std::getenv("DISPLAY");
    if (display == nullptr || display[0] == '\0') {
        GTEST_SKIP() << "DISPLAY is not set";
    }
    ContextOptions options;
    options.backend = GlBackend::Glfw;
    options.width = 32;
    options.height = 16;
    for (int round = 0; round < 2; ++round) {
        Result<std::unique_ptr<GlContext>> context = GlContext::create(options);
        ASSERT_TRUE(context.ok()) << context.error().message;
        EXPECT_EQ((*context)->backend(), GlBackend::Glfw);
        EXPECT_GE((*context)->glVersion(), 45);
        EXPECT_NE((*context)->nativeWindow(), nullptr);
        EXPECT_FALSE((*context)->shouldClose());
        expectClearAndReadBack();
        (*context)->pollEvents();
        (*context)->swapBuffers();
    }
}

}  // namespace
}  // namespace sylva::render
