// Test helpers shared by the SceneRenderer tests (headless, llvmpipe):
// - SceneRenderFixture: a GL context and a SceneRenderer made for every test;
// (Holes in a frame: core/scene/FrameHoles, shared with the viewer bench.)
#pragma once

#include <gtest/gtest.h>

#include <memory>

#include "sylva/core/scene/FrameHoles.h"
#include "sylva/render/gl/GlContext.h"
#include "sylva/render/scene/SceneRenderer.h"

namespace sylva::render {

// Fails the test (fatally, in SetUp) when no context or renderer can be made.
class SceneRenderFixture : public ::testing::Test {
protected:
    void SetUp() override {
        Result<std::unique_ptr<GlContext>> created = GlContext::create({});
        ASSERT_TRUE(created) << created.error().message;
        context_ = std::move(created.value());
        Result<std::unique_ptr<SceneRenderer>> renderer =
            SceneRenderer::create(ShaderLibrary(), TerrainSettings{});
        ASSERT_TRUE(renderer) << renderer.error().message;
        renderer_ = std::move(renderer.value());
    }
    // The renderer's GL objects go before the context they live in.
    void TearDown() override {
        renderer_.reset();
        context_.reset();
    }

    std::unique_ptr<GlContext> context_;
    std::unique_ptr<SceneRenderer> renderer_;
};

}  // namespace sylva::render
