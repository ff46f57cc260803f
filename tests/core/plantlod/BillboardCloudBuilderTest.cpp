#include "sylva/core/plantlod/BillboardCloudBuilder.h"

#include <gtest/gtest.h>

#include "sylva/core/plantlod/PlantGenerator.h"
#include "sylva/core/plantlod/PlantLodBuilder.h"

namespace sylva {
namespace {

PlantModel tree(const std::string& preset, int leaves) {
    PlantGeneratorOptions options;
    options.seed = 21;
    options.leafCount = leaves;
    return PlantGenerator::generate(PlantGenerator::preset(preset).value(), options).value();
}

TEST(BillboardCloudBuilder, LevelsHaveFewerPlanesWithinBudget) {
    for (const std::string preset : {"bush", "oak"}) {
        const PlantModel model = tree(preset, 2000);
        Result<BillboardCloud> cloud = BillboardCloudBuilder::build(model);
        ASSERT_TRUE(cloud) << cloud.error().message;
        ASSERT_GE(cloud->levels.size(), 2u) << preset;
        for (std::size_t k = 0; k < cloud->levels.size(); ++k) {
            const BillboardLevel& level = cloud->levels[k];
            std::printf("%s level %zu: epsilon %.3f m, %zu planes, atlas %dx%d\n", preset.c_str(),
                        k, double(level.epsilon), level.quads.size(), level.atlas.width,
                        level.atlas.height);
            EXPECT_GE(level.quads.size(), 3u) << preset << " level " << k;
            EXPECT_LE(level.quads.size(), 30u) << preset << " level " << k;
            if (k > 0) {
                EXPECT_LT(level.quads.size(), cloud->levels[k - 1].quads.size())
                    << preset << " level " << k;
                EXPECT_GT(level.epsilon, cloud->levels[k - 1].epsilon);
            }
        }
    }
}

// Distance of every leaf triangle's (original) vertices to its plane: at most 2ε of the
// level (a vertex welded onto an earlier plane moves by ≤ ε, then lies within ε of its
// own) plus the welding displacement of all finer levels (≤ ε each).
TEST(BillboardCloudBuilder, LeafTrianglesLieWithinTheToleranceOfTheirPlane) {
    const PlantModel model = tree("bush", 3000);
    Result<BillboardCloud> cloud = BillboardCloudBuilder::build(model);
    ASSERT_TRUE(cloud) << cloud.error().message;
    float finer = 0.0f;
    for (const BillboardLevel& level : cloud->levels) {
        const float tolerance = 2.0f * level.epsilon + finer + 1e-4f;
        std::size_t triangle = 0;
        std::size_t leaves = 0;
        float worst = 0.0f;
        for (const PlantMesh& mesh : model.meshes) {
            for (std::size_t t = 0; t < mesh.indices.size(); t += 3, ++triangle) {
                const int plane = level.trianglePlane[triangle];
                if (mesh.part != PlantPart::Leaf) {
                    if (plane >= 0) {
                        EXPECT_EQ(level.quads[std::size_t(plane)].part, PlantPart::Branch);
                    }
                    continue;
                }
                ASSERT_GE(plane, 0) << "leaf triangle " << triangle << " not simplified";
                const BillboardQuad& quad = level.quads[std::size_t(plane)];
                EXPECT_EQ(quad.part, PlantPart::Leaf);
                EXPECT_FALSE(quad.cardboard);
                for (std::size_t c = 0; c < 3; ++c) {
                    const float distance = std::abs(glm::dot(
                        mesh.positions[mesh.indices[t + c]] - quad.corners[0], quad.normal));
                    worst = std::max(worst, distance);
                }
                ++leaves;
            }
        }
        EXPECT_EQ(leaves, 6000u);
        EXPECT_LE(worst, tolerance) << "epsilon " << level.epsilon;
        finer += level.epsilon;
    }
}

TEST(BillboardCloudBuilder, AtlasHasBinaryAlphaAndQuadsPointIntoIt) {
    const PlantModel model = tree("bush", 1000);
    Result<BillboardCloud> cloud = BillboardCloudBuilder::build(model);
    ASSERT_TRUE(cloud) << cloud.error().message;
    const BillboardLevel& level = cloud->levels.front();
    std::size_t opaque = 0;
    for (std::size_t i = 3; i < level.atlas.rgba.size(); i += 4) {
        ASSERT_TRUE(level.atlas.rgba[i] == 0 || level.atlas.rgba[i] == 255);
        opaque += level.atlas.rgba[i] == 255 ? 1 : 0;
    }
    EXPECT_GT(opaque, 100u);
    bool cardboard = false;
    for (const BillboardQuad& quad : level.quads) {
        cardboard = cardboard || quad.cardboard;
        for (const glm::vec2& uv : quad.atlasUvs) {
            EXPECT_GE(uv.x, 0.0f);
            EXPECT_LE(uv.x, 1.0f);
            EXPECT_GE(uv.y, 0.0f);
            EXPECT_LE(uv.y, 1.0f);
        }
        // Corners lie on the plane and wind counter-clockwise around the normal.
        const glm::vec3 winding =
            glm::cross(quad.corners[1] - quad.corners[0], quad.corners[2] - quad.corners[0]);
        EXPECT_GT(glm::dot(winding, quad.normal), 0.0f);
        EXPECT_NEAR(glm::dot(quad.corners[2] - quad.corners[0], quad.normal), 0.0f, 1e-4f);
    }
    EXPECT_TRUE(cardboard) << "the bush's stems get cardboard cross planes";
}

TEST(BillboardCloudBuilder, HorizontalPenaltyTiltsPlanesUp) {
    // Stacked horizontal leaf layers: without the penalty they collapse into horizontal
    // planes; with the maximum penalty fewer planes are horizontal.
    const PlantModel model = tree("oak", 2000);
    BillboardCloudOptions without;
    without.horizontalPenalty = 0.0f;
    without.epsilons = {0.12f};
    BillboardCloudOptions with = without;
    with.horizontalPenalty = 0.9f;
    auto horizontal = [](const BillboardCloud& cloud) {
        std::size_t count = 0;
        for (const BillboardQuad& quad : cloud.levels.front().quads) {
            count += std::abs(quad.normal.z) > std::cos(0.35f) ? 1 : 0;
        }
        return count;
    };
    Result<BillboardCloud> a = BillboardCloudBuilder::build(model, without);
    Result<BillboardCloud> b = BillboardCloudBuilder::build(model, with);
    ASSERT_TRUE(a && b);
    EXPECT_LE(horizontal(*b), horizontal(*a));
}

TEST(BillboardCloudBuilder, BadOptionsAreReported) {
    BillboardCloudOptions options;
    options.epsilons = {1.5f};
    Result<BillboardCloud> cloud = BillboardCloudBuilder::build(tree("bush", 100), options);
    ASSERT_FALSE(cloud);
    EXPECT_EQ(cloud.error().message,
              "billboard cloud of 'bush': epsilons must lie in (0, 1) of the bounding radius");
    // More levels than the vegetation renderer's run keys hold (kMaxBillboardLevels).
    options.epsilons.assign(kMaxBillboardLevels + 1, 0.5f);
    cloud = BillboardCloudBuilder::build(tree("bush", 100), options);
    ASSERT_FALSE(cloud);
    EXPECT_EQ(cloud.error().message,
              "billboard cloud of 'bush': 17 epsilons, at most 16 levels are supported");
}

}  // namespace
}  // namespace sylva

namespace sylva {
namespace {

// addBillboardClouds measures each level with the ellipsoid levels' metric: the source
// against itself is exact, coarser clouds are worse than no error, and the stored size is
// the quads' vertices plus the atlas.
TEST(BillboardCloudBuilder, LevelsCarryTheirImageErrorAndBytes) {
    const PlantModel model = tree("bush", 300);
    PlantLodOptions options;
    options.threads = 2;
    EXPECT_EQ(plantMeshImageError(model, model, options), 0.0);
    PlantLod lod;
    ASSERT_TRUE(addBillboardClouds(model, lod, options));
    ASSERT_GE(lod.billboards.levels.size(), 2u);
    for (const BillboardLevel& level : lod.billboards.levels) {
        EXPECT_GT(level.imageError, 0.0f);
        EXPECT_LT(level.imageError, 0.2f);
        EXPECT_FLOAT_EQ(level.imageError,
                        float(plantMeshImageError(
                            model, BillboardCloudBuilder::levelModel(level, "bush"), options)));
        EXPECT_EQ(level.byteSize(), level.quads.size() * 80u +
                                        std::uint64_t(level.atlas.width) * level.atlas.height * 4u);
    }
    // An empty model cannot have billboard clouds: the error names the plant.
    PlantModel empty;
    empty.name = "nothing";
    Status failed = addBillboardClouds(empty, lod, options);
    ASSERT_FALSE(failed);
    EXPECT_EQ(failed.error().message.rfind("plant 'nothing': billboard clouds: ", 0), 0u)
        << failed.error().message;
}

}  // namespace
}  // namespace sylva
