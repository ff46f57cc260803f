// ShaderLibrary preprocessing (#include, #line, errors), embedded vs on-disk sources, and
// ShaderProgram compile errors, uniforms, drawing and compute on Mesa llvmpipe.
#include "sylva/render/gl/ShaderLibrary.h"

#include <glad/gl.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <optional>
#include <string>

#include "ScopedEnv.h"
#include "sylva/render/gl/Framebuffer.h"
#include "sylva/render/gl/GlContext.h"
#include "sylva/render/gl/ShaderProgram.h"

namespace sylva::render {
namespace {

const std::string kTestDir = std::string(SYLVA_TEST_DATA_DIR) + "/render/shaders-test";

using test::ScopedEnv;

class ShaderLibraryTest : public testing::Test {
protected:
    static void SetUpTestSuite() {
        ContextOptions options;
        options.backend = GlBackend::Egl;
        Result<std::unique_ptr<GlContext>> created = GlContext::create(options);
        ASSERT_TRUE(created.ok()) << created.error().message;
        context_ = std::move(*created).release();
    }
    static void TearDownTestSuite() {
        delete context_;
        context_ = nullptr;
    }
    void SetUp() override {
        ASSERT_NE(context_, nullptr);
        context_->makeCurrent();
    }

    ShaderLibrary disk_ = ShaderLibrary::fromDirectory(kTestDir);
    static GlContext* context_;
};

GlContext* ShaderLibraryTest::context_ = nullptr;

TEST_F(ShaderLibraryTest, ResolvesIncludesOnceWithLineDirectives) {
    Result<PreprocessedShader> result = disk_.preprocessWithMap("include/main.frag");
    ASSERT_TRUE(result.ok()) << result.error().message;
    const std::string expected =
        "#version 450 core\n"
        "#line 1 0\n"
        "\n"
        "// Includes lib/color.glsl twice: the second one must be skipped.\n"
        "#line 100001 1\n"
        "// Colour helpers for include/main.frag.\n"
        "#line 200001 2\n"
        "// Found through the shaders root (not next to include/lib/color.glsl).\n"
        "const float kHalf = 0.5;\n"
        "#line 100003 1\n"
        "#line 300001 3\n"
        "// Found next to include/lib/color.glsl.\n"
        "const float kOne = 1.0;\n"
        "#line 100004 1\n"
        "vec3 helperColor() { return vec3(kHalf, kOne, 0.0); }\n"
        "#line 4 0\n"
        "\n"
        "layout(location = 0) out vec4 fragColor;\n"
        "void main() { fragColor = vec4(helperColor(), 1.0); }\n";
    EXPECT_EQ(result->source, expected);
    const std::vector<std::string> files = {
        kTestDir + "/include/main.frag", kTestDir + "/include/lib/color.glsl",
        kTestDir + "/common.glsl", kTestDir + "/include/lib/constants.glsl"};
    EXPECT_EQ(result->files, files);

    Result<std::string> plain = disk_.preprocess("include/main.frag");
    ASSERT_TRUE(plain.ok());
    EXPECT_EQ(*plain, expected);

    Result<ShaderProgram> program =
        ShaderProgram::create(disk_, {{GL_FRAGMENT_SHADER, "include/main.frag"}});
    EXPECT_TRUE(program.ok()) << program.error().message;
}

TEST_F(ShaderLibraryTest, InsertsDefinesAfterVersion) {
    Result<PreprocessedShader> result =
        disk_.preprocessWithMap("include/main.frag", "#define FOO 1\n#define BAR 2");
    ASSERT_TRUE(result.ok()) << result.error().message;
    EXPECT_EQ(
        result->source.rfind("#version 450 core\n#line 100001 1\n#define FOO 1\n#define BAR 2\n"
                             "#line 1 0\n",
                             0),
        0u)
        << result->source;
    ASSERT_GE(result->files.size(), 2u);
    EXPECT_EQ(result->files[1], "<defines>");
}

TEST_F(ShaderLibraryTest, IncludeCycleNamesTheChain) {
    Result<std::string> result = disk_.preprocess("cycle/main.frag");
    ASSERT_FALSE(result.ok());
    EXPECT_EQ(result.error().message, kTestDir + "/cycle/b.glsl:2: include cycle: " + kTestDir +
                                          "/cycle/a.glsl -> " + kTestDir + "/cycle/b.glsl -> " +
                                          kTestDir + "/cycle/a.glsl");
}

TEST_F(ShaderLibraryTest, MissingIncludeNamesWhereItLooked) {
    Result<std::string> result = disk_.preprocess("missing/main.frag");
    ASSERT_FALSE(result.ok());
    EXPECT_EQ(result.error().message,
              kTestDir +
                  "/missing/main.frag:3: cannot find include \"does_not_exist.glsl\" (tried " +
                  kTestDir + "/missing/does_not_exist.glsl, " + kTestDir + "/does_not_exist.glsl)");
}

TEST_F(ShaderLibraryTest, MissingFileNamesTheFullPath) {
    Result<std::string> result = disk_.preprocess("nope/nothing.frag");
    ASSERT_FALSE(result.ok());
    EXPECT_EQ(result.error().message, "shader file not found: " + kTestDir + "/nope/nothing.frag");
}

TEST_F(ShaderLibraryTest, CompileErrorNamesTheIncludedFileAndLine) {
    Result<ShaderProgram> program =
        ShaderProgram::create(disk_, {{GL_FRAGMENT_SHADER, "broken/main.frag"}});
    ASSERT_FALSE(program.ok());
    const std::string& message = program.error().message;
    EXPECT_NE(message.find("compiling fragment shader " + kTestDir + "/broken/main.frag failed"),
              std::string::npos)
        << message;
    EXPECT_NE(message.find(kTestDir + "/broken/broken_lib.glsl:3: error:"), std::string::npos)
        << message;
    // Mesa reports this one with source-string 0; the line number still finds the file.
    EXPECT_NE(
        message.find(kTestDir + "/broken/broken_lib.glsl:3: error: `undeclaredThing' undeclared"),
        std::string::npos)
        << message;
}

TEST_F(ShaderLibraryTest, CompileErrorInTheMainFileAfterDefines) {
    // Line 5 of broken/main.frag calls broken(); make it fail there by hiding broken_lib's
    // error behind a define that is not used: the error must still map to broken_lib:3,
    // with the defines' lines not shifting anything.
    Result<ShaderProgram> program = ShaderProgram::create(
        disk_, {{GL_FRAGMENT_SHADER, "broken/main.frag"}}, "#define A 1\n#define B 2\n");
    ASSERT_FALSE(program.ok());
    EXPECT_NE(program.error().message.find(kTestDir + "/broken/broken_lib.glsl:3: error:"),
              std::string::npos)
        << program.error().message;
}

TEST(PreprocessedShaderTest, TranslatesDriverLogFormats) {
    PreprocessedShader shader;
    shader.files = {"shaders/a.frag", "shaders/lib/b.glsl"};
    // The file comes from the line number (index * kLineStride + line), not from the
    // source-string number, which Mesa often reports as 0.
    EXPECT_EQ(shader.translateLog("0:12(3): error: `x' undeclared\n"
                                  "1:100004(10): warning: unused\n"
                                  "0:100009(2): error: Mesa lost the source string\n"
                                  "7:700001(1): error: unknown file\n"
                                  "plain line"),
              "shaders/a.frag:12: error: `x' undeclared\n"
              "shaders/lib/b.glsl:4: warning: unused\n"
              "shaders/lib/b.glsl:9: error: Mesa lost the source string\n"
              "7:700001(1): error: unknown file\n"
              "plain line\n");
    EXPECT_EQ(shader.translateLog("1(100007) : error C1008: undefined variable \"x\""),
              "shaders/lib/b.glsl:7: error C1008: undefined variable \"x\"\n");
    EXPECT_EQ(shader.translateLog("ERROR: 0:5: 'x' : undeclared identifier"),
              "ERROR: shaders/a.frag:5: 'x' : undeclared identifier\n");
}

TEST_F(ShaderLibraryTest, SylvaShaderDirOverridesTheEmbeddedTable) {
    {
        ScopedEnv env("SYLVA_SHADER_DIR", kTestDir.c_str());
        ShaderLibrary library;
        EXPECT_TRUE(library.readsFromDisk());
        Result<std::string> common = library.load("common.glsl");
        ASSERT_TRUE(common.ok()) << common.error().message;
        EXPECT_NE(common->find("kHalf"), std::string::npos);
        EXPECT_EQ(library.displayName("common.glsl"), kTestDir + "/common.glsl");
        Result<std::string> missing = library.load("common/fullscreen.vert");
        ASSERT_FALSE(missing.ok());
        EXPECT_EQ(missing.error().message,
                  "shader file not found: " + kTestDir + "/common/fullscreen.vert");
    }
    {
        ScopedEnv env("SYLVA_SHADER_DIR", nullptr);
        ShaderLibrary library;
        EXPECT_FALSE(library.readsFromDisk());
        EXPECT_EQ(library.displayName("common/fullscreen.vert"), "shaders/common/fullscreen.vert");
        Result<std::string> vertex = library.load("common/fullscreen.vert");
        ASSERT_TRUE(vertex.ok()) << vertex.error().message;
        EXPECT_EQ(vertex->rfind("#version 450 core\n", 0), 0u);
        EXPECT_FALSE(library.load("common.glsl").ok());
    }
}

TEST_F(ShaderLibraryTest, EmbedsEveryShaderFile) {
    const std::vector<std::string> paths = ShaderLibrary::embeddedPaths();
    EXPECT_TRUE(std::is_sorted(paths.begin(), paths.end()));
    for (const char* path : {"common/fullscreen.vert", "common/constant_color.frag"}) {
        EXPECT_NE(std::find(paths.begin(), paths.end(), path), paths.end()) << path;
    }
}

TEST_F(ShaderLibraryTest, DrawsAFullScreenTriangle) {
    const ShaderLibrary library = ShaderLibrary::embedded();
    Result<ShaderProgram> program =
        ShaderProgram::create(library, {{GL_VERTEX_SHADER, "common/fullscreen.vert"},
                                        {GL_FRAGMENT_SHADER, "common/constant_color.frag"}});
    ASSERT_TRUE(program.ok()) << program.error().message;
    EXPECT_NE(program->id(), 0u);
    EXPECT_GE(program->uniformLocation("uColor"), 0);
    EXPECT_EQ(program->uniformLocation("noSuchUniform"), -1);
    program->setVec4("uColor", {0.2f, 0.4f, 0.6f, 1.0f});
    program->setFloat("noSuchUniform", 1.0f);  // ignored, no GL error

    Result<Framebuffer> framebuffer = Framebuffer::create(16, 12, {GL_RGBA8}, false);
    ASSERT_TRUE(framebuffer.ok()) << framebuffer.error().message;
    framebuffer->bind();
    framebuffer->clearColor(0, {0.0f, 0.0f, 0.0f, 0.0f});
    GLuint vertexArray = 0;
    glCreateVertexArrays(1, &vertexArray);
    glBindVertexArray(vertexArray);
    program->use();
    glDrawArrays(GL_TRIANGLES, 0, 3);
    glBindVertexArray(0);
    glDeleteVertexArrays(1, &vertexArray);
    Framebuffer::unbind();
    EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));

    const std::vector<std::uint8_t> pixels = framebuffer->readPixelsRGBA8(0);
    ASSERT_EQ(pixels.size(), 16u * 12u * 4u);
    for (std::size_t i = 0; i < pixels.size(); i += 4) {
        ASSERT_EQ(pixels[i], 51) << "pixel " << i / 4;
        ASSERT_EQ(pixels[i + 1], 102) << "pixel " << i / 4;
        ASSERT_EQ(pixels[i + 2], 153) << "pixel " << i / 4;
        ASSERT_EQ(pixels[i + 3], 255) << "pixel " << i / 4;
    }

    ShaderProgram moved = std::move(*program);
    EXPECT_EQ(program->id(), 0u);
    EXPECT_NE(moved.id(), 0u);
}

TEST_F(ShaderLibraryTest, ComputeShaderWritesAnImage) {
    constexpr int kWidth = 5;
    constexpr int kHeight = 3;
    Result<ShaderProgram> program = ShaderProgram::create(
        disk_, {{GL_COMPUTE_SHADER, "compute/fill.comp"}}, "#define FILL_W 2.0\n");
    ASSERT_TRUE(program.ok()) << program.error().message;
    Result<Framebuffer> framebuffer = Framebuffer::create(kWidth, kHeight, {GL_RGBA32F}, false);
    ASSERT_TRUE(framebuffer.ok()) << framebuffer.error().message;

    program->setFloat("uValue", 1.0f);
    program->use();
    glBindImageTexture(0, framebuffer->colorTexture(0), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    glDispatchCompute((kWidth + 7) / 8, (kHeight + 7) / 8, 1);
    glMemoryBarrier(GL_FRAMEBUFFER_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
    EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));

    const std::vector<float> texels = framebuffer->readPixelsFloat(0, 4);
    ASSERT_EQ(texels.size(), static_cast<std::size_t>(kWidth * kHeight * 4));
    for (int row = 0; row < kHeight; ++row) {
        for (int x = 0; x < kWidth; ++x) {
            const float* texel = &texels[static_cast<std::size_t>((row * kWidth + x) * 4)];
            EXPECT_EQ(texel[0], static_cast<float>(x));
            EXPECT_EQ(texel[1], static_cast<float>(kHeight - 1 - row));  // rows top to bottom
            EXPECT_EQ(texel[2], 1.5f);
            EXPECT_EQ(texel[3], 2.0f);
        }
    }
}

TEST_F(ShaderLibraryTest, RejectsBadStageLists) {
    Result<ShaderProgram> empty = ShaderProgram::create(disk_, {});
    ASSERT_FALSE(empty.ok());
    EXPECT_EQ(empty.error().message, "ShaderProgram: no shader stages given");
    Result<ShaderProgram> twice = ShaderProgram::create(
        disk_, {{GL_FRAGMENT_SHADER, "include/main.frag"}, {GL_FRAGMENT_SHADER, "x.frag"}});
    ASSERT_FALSE(twice.ok());
    EXPECT_EQ(twice.error().message,
              "ShaderProgram: two fragment shaders (include/main.frag, x.frag)");
}

}  // namespace
}  // namespace sylva::render
