// Test helpers shared by the SceneRenderer tests (headless, llvmpipe):
// - SceneRenderFixture: a GL context and a SceneRenderer made for every test;
// - countHoles: sky pixels of a rendered frame whose ray passes under the ground, as the
//   viewer bench counts them (bench/ViewerBenchmark.cpp, `frames_with_holes`, issue 20).
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <memory>
#include <vector>

#include "sylva/core/geo/Ellipsoid.h"
#include "sylva/core/scene/Camera.h"
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

struct HoleCount {
    int deepRays = 0;  // rays passing more than 50 m under the ellipsoid
    int holes = 0;     // of those, pixels showing sky
};

// Over `depth` (reversed-Z, width x height, row 0 at the top: SceneRenderer::depth() of a
// frame `camera` rendered): the pixels whose ray (not the line behind the camera) passes
// more than 50 m under the ellipsoid, made a sphere by scaling z, and of those the ones
// showing sky (depth 0). Over a terrain at or above sea level every such ray should meet
// the ground.
inline HoleCount countHoles(const Camera& camera, const std::vector<float>& depth, int width,
                            int height) {
    constexpr double kHoleDepth = 50.0;
    const double scale = Ellipsoid::kSemiMajorAxis / Ellipsoid::kSemiMinorAxis;
    const glm::dvec3 origin(camera.position.x, camera.position.y, camera.position.z * scale);
    const double inner = Ellipsoid::kSemiMajorAxis - kHoleDepth;
    const double tanHalf = std::tan(camera.verticalFov / 2);
    const double aspect = double(width) / height;
    HoleCount count;
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const glm::dvec3 view(((x + 0.5) / width * 2 - 1) * tanHalf * aspect,
                                  (1 - (y + 0.5) / height * 2) * tanHalf, -1.0);
            glm::dvec3 direction = camera.axes * glm::normalize(view);
            direction.z *= scale;
            const double qa = glm::dot(direction, direction);
            const double qb = 2.0 * glm::dot(origin, direction);
            const double qc = glm::dot(origin, origin) - inner * inner;
            const double discriminant = qb * qb - 4 * qa * qc;
            if (discriminant < 0.0 || -qb - std::sqrt(discriminant) <= 0.0) {
                continue;  // the ray (not the line behind the camera) stays above
            }
            ++count.deepRays;
            count.holes += depth[std::size_t(y) * width + x] <= 0.0f ? 1 : 0;
        }
    }
    return count;
}

}  // namespace sylva::render
