// The `dmbbc` vegetation method (seed 000 ch. 5) against an analytic case: one billboard
// quad standing for a tilted square. Ray-marched with its displacement, every pixel of the
// square is drawn at the tilted square's depth (within the texel and step quantisation);
// the flat billboard cloud drawn from the same level misses it by up to 0.2 m, which this
// test also checks, so that flattening the displacement fails it. A two-colour atlas checks
// that the atlas and the heights are read the right way up.
#include <gtest/gtest.h>

#include <glad/gl.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "sylva/core/geo/Ellipsoid.h"
#include "sylva/render/gl/Framebuffer.h"
#include "sylva/render/gl/GlContext.h"
#include "sylva/render/scene/SceneRenderer.h"
#include "sylva/render/vegetation/VegetationRenderer.h"

namespace sylva::render {
namespace {

constexpr double kDegree = std::numbers::pi / 180;

// A 2 m × 2 m square tilted about x (y = 0.2 (z − 1.5)), green; one billboard level of one
// quad in the plane y = 0 facing −y (towards the camera), an opaque 64² atlas.
std::shared_ptr<PlantAsset> tiltedAsset() {
    auto asset = std::make_shared<PlantAsset>();
    asset->name = "tilted";
    PlantMaterial material;
    material.baseColor = glm::vec4(0.1f, 0.5f, 0.1f, 1.0f);
    asset->model.materials.push_back(material);
    PlantMesh mesh;
    mesh.part = PlantPart::Leaf;
    mesh.material = 0;
    mesh.positions = {{-1, -0.25f, 0.5f}, {1, -0.25f, 0.5f}, {1, 0.15f, 2.5f}, {-1, 0.15f, 2.5f}};
    mesh.normals.assign(4, glm::normalize(glm::vec3(0, -1, 0.2f)));
    mesh.indices = {0, 1, 2, 0, 2, 3};
    asset->model.meshes.push_back(mesh);
    BillboardLevel level;
    BillboardQuad quad;
    quad.corners[0] = {-1, 0, 0.5f};
    quad.corners[1] = {1, 0, 0.5f};
    quad.corners[2] = {1, 0, 2.5f};
    quad.corners[3] = {-1, 0, 2.5f};
    quad.atlasUvs[0] = {0, 1};
    quad.atlasUvs[1] = {1, 1};
    quad.atlasUvs[2] = {1, 0};
    quad.atlasUvs[3] = {0, 0};
    quad.normal = {0, -1, 0};
    level.epsilon = 0.25f;
    level.quads = {quad};
    level.trianglePlane = {0, 0};
    level.atlas.width = level.atlas.height = 64;
    level.atlas.rgba.assign(64 * 64 * 4, 255);
    // Rows from the top: the upper half red, the lower half green (the orientation check).
    for (std::size_t texel = 0; texel < 64 * 64; ++texel) {
        const bool upper = texel < 32 * 64;
        level.atlas.rgba[texel * 4 + 0] = upper ? 255 : 0;
        level.atlas.rgba[texel * 4 + 1] = upper ? 0 : 255;
        level.atlas.rgba[texel * 4 + 2] = 0;
    }
    asset->lod.billboards.levels.push_back(level);
    asset->lod.boundsMinimum = glm::vec3(-1, -0.2f, 0.5f);
    asset->lod.boundsMaximum = glm::vec3(1, 0.2f, 2.5f);
    return asset;
}

struct Depths {
    std::vector<float> depth, albedo;
};

Depths render(VegetationRenderer& renderer, const InstanceBatch& batch, const Camera& c,
              VegetationMethod method, int width, int height, double near) {
    Result<Framebuffer> gbuffer =
        Framebuffer::create(width, height, {GL_RGBA16F, GL_RGBA16F}, true);
    EXPECT_TRUE(gbuffer);
    glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
    gbuffer.value().bind();
    gbuffer.value().clearColor(0, glm::vec4(0.0f));
    gbuffer.value().clearColor(1, glm::vec4(0.0f));
    gbuffer.value().clearDepth(0.0f);
    VegetationSettings settings;
    settings.method = method;
    renderer.draw({&batch}, c,
                  SceneRenderer::projection(c.verticalFov, double(width) / height, near), near,
                  width, height, settings);
    Depths out{gbuffer.value().readDepth(), gbuffer.value().readPixelsFloat(0, 4)};
    Framebuffer::unbind();
    glClipControl(GL_LOWER_LEFT, GL_NEGATIVE_ONE_TO_ONE);
    return out;
}

TEST(DisplacedBillboardRenderer, RayMarchedBoxWritesTheTiltedSquaresDepth) {
    Result<std::unique_ptr<GlContext>> context = GlContext::create({});
    ASSERT_TRUE(context) << context.error().message;
    Result<std::unique_ptr<VegetationRenderer>> created =
        VegetationRenderer::create(ShaderLibrary());
    ASSERT_TRUE(created) << created.error().message;
    VegetationRenderer& renderer = *created.value();
    const Result<std::uint32_t> species = renderer.addSpecies(tiltedAsset());
    ASSERT_TRUE(species) << species.error().message;

    // The camera 1.5 m above the ground looking north, 10° up-and-down of nothing: the
    // square's centre 5 m ahead at eye height, seen from 1.2 m to the east (so the
    // rays are oblique to the box in both directions).
    Camera c;
    c.geodetic = {45.0 * kDegree, 10.0 * kDegree + 1.2 / (6367000.0 * std::cos(45.0 * kDegree)),
                  1.5};
    c.position = Ellipsoid::toEcef(c.geodetic);
    c.axes = Camera::axesFromAngles(c.geodetic, -10.0 * kDegree, 0.0, 0.0);
    c.verticalFov = 40 * kDegree;
    Geodetic base{45.0 * kDegree + 5.0 / 6367000.0, 10.0 * kDegree, 0.0};
    InstancePlacement p;
    p.baseEcef = Ellipsoid::toEcef(base);
    p.latitude = base.latitude;
    p.longitude = base.longitude;
    p.species = species.value();
    const InstanceBatch batch = LodSelector::makeBatch(p.baseEcef, {p}, renderer.speciesLods());
    constexpr int kWidth = 320, kHeight = 240;
    const double near = 0.5;
    const Depths displaced =
        render(renderer, batch, c, VegetationMethod::DisplacedBillboard, kWidth, kHeight, near);
    ASSERT_EQ(renderer.statistics().billboardInstances, 1u);
    const Depths flat =
        render(renderer, batch, c, VegetationMethod::Billboard, kWidth, kHeight, near);

    // The tilted square in view space: a point of the model frame → view (double).
    const InstanceBatch::Instance& instance = batch.instances[0];
    const glm::dmat3 view = c.viewRotation();
    const glm::dmat3 axes(glm::dvec3(instance.axes[0]), glm::dvec3(instance.axes[1]),
                          glm::dvec3(instance.axes[2]));
    const auto toView = [&](glm::dvec3 model) {
        return view * (batch.origin - c.position + glm::dvec3(instance.base) + axes * model);
    };
    const glm::dvec3 origin = toView({-1, -0.25, 0.5});
    const glm::dvec3 edgeS = toView({1, -0.25, 0.5}) - origin;
    const glm::dvec3 edgeT = toView({-1, 0.15, 2.5}) - origin;
    const glm::dvec3 normal = glm::normalize(glm::cross(edgeS, edgeT));
    const double f = 1.0 / std::tan(c.verticalFov / 2), aspect = double(kWidth) / kHeight;
    int inside = 0, covered = 0, close = 0, outsideDrawn = 0, wrongColour = 0;
    double worst = 0.0, worstFlat = 0.0;
    for (int y = 0; y < kHeight; ++y) {
        for (int x = 0; x < kWidth; ++x) {
            const glm::dvec3 ray(((x + 0.5) / kWidth * 2 - 1) * aspect / f,
                                 (1 - (y + 0.5) / kHeight * 2) / f, -1.0);
            const double t = glm::dot(origin, normal) / glm::dot(ray, normal);
            const glm::dvec3 hit = ray * t - origin;
            const double s = glm::dot(hit, edgeS) / glm::dot(edgeS, edgeS);
            const double u = glm::dot(hit, edgeT) / glm::dot(edgeT, edgeT);
            const std::size_t i = std::size_t(y) * kWidth + x;
            const bool drawn = displaced.albedo[i * 4 + 3] > 0.0f;
            if (s < -0.05 || s > 1.05 || u < -0.05 || u > 1.05) {
                outsideDrawn += drawn ? 1 : 0;
                continue;
            }
            if (s < 0.03 || s > 0.97 || u < 0.03 || u > 0.97) {
                continue;
            }
            ++inside;
            if (!drawn) {
                continue;
            }
            ++covered;
            // Colour: red above the square's middle, green below (well away from it).
            const float red = displaced.albedo[i * 4], green = displaced.albedo[i * 4 + 1];
            if (u > 0.6) {
                wrongColour += red > green ? 0 : 1;
            } else if (u < 0.4) {
                wrongColour += green > red ? 0 : 1;
            }
            const double error = std::abs(near / displaced.depth[i] - t);  // t: distance along −z
            worst = std::max(worst, error);
            close += error < 0.02 ? 1 : 0;
            if (flat.depth[i] > 0.0f) {
                worstFlat = std::max(worstFlat, std::abs(near / flat.depth[i] - t));
            }
        }
    }
    EXPECT_GT(inside, 3000);
    EXPECT_EQ(covered, inside);
    EXPECT_EQ(outsideDrawn, 0);
    EXPECT_EQ(wrongColour, 0);
    EXPECT_GE(close, covered * 99 / 100) << "worst " << worst;
    EXPECT_LT(worst, 0.05);
    EXPECT_GT(worstFlat, 0.15);  // the flat quad is up to 0.2 m off: the test sees flattening
    std::printf("dmbbc: %d pixels, worst depth error %.4f m (flat billboard %.4f m)\n", inside,
                worst, worstFlat);
}

}  // namespace
}  // namespace sylva::render
