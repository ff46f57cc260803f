// GlHandle on a real context (llvmpipe): a handle owns exactly one GL object. glIs* tells
// whether the name still names an object, so each kind is checked for: moves transfer the
// object and leave the source empty, a moved-from handle deletes nothing when destroyed,
// destroying (or assigning over, or resetting) the owner deletes it, release() does not.
#include "sylva/render/gl/GlHandle.h"

#include <glad/gl.h>

#include <gtest/gtest.h>

#include <functional>
#include <memory>
#include <utility>

#include "sylva/render/gl/GlContext.h"

namespace sylva::render {
namespace {

class GlHandleTest : public ::testing::Test {
public:
    static void SetUpTestSuite() {
        Result<std::unique_ptr<GlContext>> created = GlContext::create({});
        ASSERT_TRUE(created) << created.error().message;
        context_ = std::move(created.value()).release();
    }
    static void TearDownTestSuite() {
        delete context_;
        context_ = nullptr;
    }

protected:
    void SetUp() override {
        ASSERT_NE(context_, nullptr);
        context_->makeCurrent();
    }
    static GlContext* context_;
};

GlContext* GlHandleTest::context_ = nullptr;

using Exists = std::function<bool(std::uint32_t)>;

template <typename Handle>
void expectMovesAndDestructionDelete(const std::function<Handle()>& create, const Exists& exists) {
    std::uint32_t id = 0;
    {
        Handle owner = create();
        id = owner.get();
        ASSERT_NE(id, 0u);
        ASSERT_TRUE(exists(id));
        {
            Handle moved(std::move(owner));
            EXPECT_EQ(owner.get(), 0u);
            EXPECT_FALSE(owner);
            EXPECT_EQ(moved.get(), id);
            Handle assigned;
            assigned = std::move(moved);
            EXPECT_EQ(moved.get(), 0u);
            EXPECT_EQ(assigned.get(), id);
            owner = std::move(assigned);
        }  // `moved` and `assigned` end empty: nothing deleted
        EXPECT_EQ(owner.get(), id);
        EXPECT_TRUE(exists(id));
    }
    EXPECT_FALSE(exists(id));  // the owner's destructor deleted it

    Handle first = create();
    Handle second = create();
    const std::uint32_t replaced = first.get();
    const std::uint32_t kept = second.get();
    first = std::move(second);  // deletes what `first` owned
    EXPECT_FALSE(exists(replaced));
    EXPECT_TRUE(exists(kept));
    first.reset();
    EXPECT_FALSE(exists(kept));
    EXPECT_FALSE(first);

    Handle released = create();
    const std::uint32_t free = released.release();
    EXPECT_FALSE(released);
    EXPECT_TRUE(exists(free));
    Handle adopted(free);  // owned again, so deleted at the end of the scope
    EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

TEST_F(GlHandleTest, BuffersAndVertexArrays) {
    expectMovesAndDestructionDelete<GlBuffer>(createGlBuffer,
                                              [](std::uint32_t id) { return glIsBuffer(id); });
    expectMovesAndDestructionDelete<GlVertexArray>(
        createGlVertexArray, [](std::uint32_t id) { return glIsVertexArray(id); });
}

TEST_F(GlHandleTest, TexturesAndFramebuffers) {
    expectMovesAndDestructionDelete<GlTexture>([] { return createGlTexture(GL_TEXTURE_2D); },
                                               [](std::uint32_t id) { return glIsTexture(id); });
    expectMovesAndDestructionDelete<GlFramebuffer>(
        createGlFramebuffer, [](std::uint32_t id) { return glIsFramebuffer(id); });
}

TEST_F(GlHandleTest, ProgramsAndShaders) {
    expectMovesAndDestructionDelete<GlProgram>(createGlProgram,
                                               [](std::uint32_t id) { return glIsProgram(id); });
    expectMovesAndDestructionDelete<GlShader>([] { return createGlShader(GL_FRAGMENT_SHADER); },
                                              [](std::uint32_t id) { return glIsShader(id); });
}

TEST_F(GlHandleTest, EmptyHandlesDeleteNothing) {
    GlBuffer empty;
    EXPECT_EQ(empty.get(), 0u);
    empty.reset();
    GlBuffer alsoEmpty(std::move(empty));
    EXPECT_FALSE(alsoEmpty);
    EXPECT_EQ(glGetError(), static_cast<GLenum>(GL_NO_ERROR));
}

}  // namespace
}  // namespace sylva::render
