// GlRequirements: the driver on this machine (llvmpipe) has every feature, and each
// shortfall gives one error naming the feature and the driver's value.
#include "sylva/render/gl/GlRequirements.h"

#include <gtest/gtest.h>

#include "sylva/render/gl/GlContext.h"

namespace sylva::render {
namespace {

TEST(GlRequirements, ThisDriverHasEveryFeature) {
    Result<std::unique_ptr<GlContext>> context = GlContext::create({});
    ASSERT_TRUE(context) << context.error().message;
    const GlFeatures features = queryGlFeatures();
    EXPECT_GE(features.vertexStorageBlocks, 2);
    EXPECT_TRUE(features.rgba32fBlendable);
    EXPECT_TRUE(checkGlFeatures(features));
}

TEST(GlRequirements, EachShortfallIsOneErrorNamingIt) {
    const GlFeatures good = requiredGlFeatures();
    EXPECT_TRUE(checkGlFeatures(good));

    GlFeatures noStorage = good;
    noStorage.vertexStorageBlocks = 0;
    Status status = checkGlFeatures(noStorage);
    ASSERT_FALSE(status);
    EXPECT_EQ(status.error().message,
              "the GL driver lacks a feature Sylva needs: GL_MAX_VERTEX_SHADER_STORAGE_BLOCKS is "
              "0, need at least 2 (for plant primitives read in vertex shaders)");

    GlFeatures fewLayers = good;
    fewLayers.arrayTextureLayers = 16;
    status = checkGlFeatures(fewLayers);
    ASSERT_FALSE(status);
    EXPECT_EQ(status.error().message,
              "the GL driver lacks a feature Sylva needs: GL_MAX_ARRAY_TEXTURE_LAYERS is 16, need "
              "at least 32 (for one layer per clipmap level)");

    GlFeatures noBlend = good;
    noBlend.rgba32fBlendable = false;
    status = checkGlFeatures(noBlend);
    ASSERT_FALSE(status);
    EXPECT_EQ(status.error().message,
              "the GL driver lacks a feature Sylva needs: blending into GL_RGBA32F textures "
              "(anti-aliasing sums)");
}

}  // namespace
}  // namespace sylva::render
