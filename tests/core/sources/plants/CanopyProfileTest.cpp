// CanopyProfile and CanopyLayerSource (the far-field canopy's layers): heights, widths
// and albedo from a hand-made LoD, the Beer-Lambert cover against the formula written
// out here, the combined elevation map's texels, and the errors.
#include "sylva/core/sources/plants/CanopyProfile.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "sylva/core/scheduler/TileEvaluator.h"
#include "sylva/core/sources/plants/CanopyLayerSource.h"
#include "sylva/core/sources/raster/ConstantSource.h"

namespace sylva {
namespace {

PlantLod lodOf(float height, float halfWidth, glm::vec3 coarseColor) {
    PlantLod lod;
    lod.name = "tree";
    lod.boundsMinimum = {-halfWidth, -2.0f * halfWidth, 0.0f};
    lod.boundsMaximum = {halfWidth, 2.0f * halfWidth, height};
    LodEllipsoid coarse;
    coarse.level = 2;
    coarse.color = coarseColor;
    coarse.weight = 3.0f;
    coarse.ambientOcclusion = 0.5f;
    LodEllipsoid other = coarse;
    other.color = glm::vec3(0.0f);
    other.weight = 1.0f;
    other.ambientOcclusion = 0.9f;
    LodEllipsoid fine = coarse;
    fine.level = 0;  // not the coarsest level: ignored
    fine.color = glm::vec3(1.0f);
    lod.ellipsoids = {coarse, other, fine};
    return lod;
}

TEST(CanopyProfile, SpeciesFromTheCoarsestLevel) {
    Result<CanopySpecies> species = CanopyProfile::species(lodOf(10.0f, 2.0f, {0.4f, 0.8f, 0.2f}));
    ASSERT_TRUE(species) << species.error().message;
    EXPECT_DOUBLE_EQ(species.value().height, 10.0);
    EXPECT_DOUBLE_EQ(species.value().crownWidth, 0.5 * (4.0 + 8.0));
    EXPECT_NEAR(species.value().sphereRadius, 0.5 * std::sqrt(16.0 + 64.0 + 100.0), 1e-6);
    EXPECT_NEAR(species.value().albedo.g, 0.8 * 3.0 / 4.0, 1e-6);
    EXPECT_NEAR(species.value().ambientOcclusion, (0.5 * 3.0 + 0.9) / 4.0, 1e-6);
}

TEST(CanopyProfile, HeightAndCoverFromDensityAndShares) {
    PlantsParameters parameters;
    parameters.perHectare = 200.0;
    parameters.scaleMinimum = 0.8;
    parameters.scaleMaximum = 1.4;  // mean 1.1
    parameters.species = {{"a", 3.0}, {"b", 1.0}};
    CanopySpecies a, b;
    a.height = 20.0;
    a.crownWidth = 6.0;
    a.sphereRadius = 11.0;
    b.height = 8.0;
    b.crownWidth = 2.0;
    b.sphereRadius = 4.0;
    Result<CanopyProfile> profile = CanopyProfile::make(parameters, {a, b});
    ASSERT_TRUE(profile) << profile.error().message;
    const CanopyProfile& p = profile.value();
    const double height = (0.75 * 20.0 + 0.25 * 8.0) * 1.1;
    const double width = (0.75 * 6.0 + 0.25 * 2.0) * 1.1;
    EXPECT_NEAR(p.height(), height, 1e-9);
    EXPECT_NEAR(p.crownWidth(), width, 1e-9);
    EXPECT_NEAR(p.smallestSphereRadius(), 4.0 * 0.8, 1e-9);
    for (const double density : {0.0, 0.05, 0.3, 1.0}) {
        const double cover = 1.0 - std::exp(-density * 0.02 * width * 100.0);
        EXPECT_NEAR(p.cover(density), cover, 1e-12) << density;
        EXPECT_NEAR(p.canopyHeight(density), height * cover, 1e-9) << density;
    }
    EXPECT_EQ(p.cover(-1.0), 0.0);
    EXPECT_EQ(p.cover(3.0), p.cover(1.0));
}

// The stand's crowns in leaf states: share- and scale²-weighted opaque areas of the
// species' coarsest levels, the colour weighted by what each shows from the side.
TEST(CanopyProfile, CrownsInALeafState) {
    PlantLod deciduous = lodOf(10.0f, 2.0f, {0.1f, 0.4f, 0.1f});
    for (LodEllipsoid& e : deciduous.ellipsoids) {
        e.center = {0.0f, 0.0f, 6.0f};
        e.radii = glm::vec3(2.0f);
        e.alphaThreshold = 0.6f;
    }
    deciduous.ellipsoids.resize(1);  // one coarse sphere (level 2)
    PlantLod evergreen = deciduous;
    evergreen.ellipsoids[0].color = {0.05f, 0.2f, 0.05f};
    evergreen.ellipsoids[0].radii = glm::vec3(1.0f);
    Result<CanopySpecies> a = CanopyProfile::species(deciduous);
    Result<CanopySpecies> b = CanopyProfile::species(evergreen);
    ASSERT_TRUE(a && b);
    EXPECT_EQ(a.value().crown.size(), 1u);
    PlantsParameters parameters;
    parameters.perHectare = 100.0;
    parameters.scaleMinimum = 0.5;
    parameters.scaleMaximum = 1.5;  // E[s²] = (0.25 + 0.75 + 2.25) / 3
    parameters.species = {{"a", 3.0}, {"b", 1.0}};
    const CanopyProfile profile = CanopyProfile::make(parameters, {a.value(), b.value()}).value();
    const double scale2 = (0.25 + 0.75 + 2.25) / 3.0, opacity = 1.0 - 0.36;
    const double discA = std::numbers::pi * 4.0, discB = std::numbers::pi;

    const CanopyCrowns summer = profile.crowns({});  // no states: full leaf
    ASSERT_EQ(summer.species.size(), 2u);
    const double full = scale2 * opacity * (0.75 * discA + 0.25 * discB);
    EXPECT_NEAR(summer.topOpaqueArea, full, 0.01 * full);
    EXPECT_NEAR(summer.sideOpaqueArea, full, 0.01 * full);
    EXPECT_NEAR(summer.sideOpaqueFraction, opacity, 0.01);
    const double greenSummer =
        (0.75 * discA * 0.4 + 0.25 * discB * 0.2) / (0.75 * discA + 0.25 * discB);
    EXPECT_NEAR(summer.albedo.g, greenSummer, 0.005);

    LeafState winter;
    winter.leafFraction = 0.0f;
    const CanopyCrowns january = profile.crowns({winter, LeafState{}});
    const double evergreenOnly = scale2 * opacity * 0.25 * discB;
    EXPECT_NEAR(january.topOpaqueArea, evergreenOnly, 0.01 * evergreenOnly);
    EXPECT_NEAR(january.albedo.g, 0.2, 1e-4);  // only the evergreen shows
    EXPECT_EQ(january.species[0].sideOpaqueArea(), 0.0);

    LeafState spring;
    spring.leafFraction = 0.5f;
    const CanopyCrowns may = profile.crowns({spring, LeafState{}});
    const double half = scale2 * opacity * (0.75 * 0.5 * discA + 0.25 * discB);
    EXPECT_NEAR(may.sideOpaqueArea, half, 0.01 * half);
    // Leaf-off everywhere: nothing opaque, the albedo falls back to the full-leaf one.
    const CanopyCrowns bare = profile.crowns({winter, winter});
    EXPECT_EQ(bare.sideOpaqueArea, 0.0);
    EXPECT_EQ(bare.albedo, profile.albedo());
}

TEST(CanopyProfile, Errors) {
    PlantsParameters parameters;
    parameters.species = {{"a", 1.0}};
    EXPECT_FALSE(CanopyProfile::make(parameters, {}));
    parameters.species = {{"a", 0.0}};
    EXPECT_FALSE(CanopyProfile::make(parameters, {CanopySpecies{}}));
    parameters.species.clear();
    EXPECT_FALSE(CanopyProfile::make(parameters, {}));
    PlantLod empty = lodOf(10.0f, 2.0f, glm::vec3(0.5f));
    empty.ellipsoids.clear();
    Result<CanopySpecies> noEllipsoids = CanopyProfile::species(empty);
    ASSERT_FALSE(noEllipsoids);
    EXPECT_NE(noEllipsoids.error().message.find("tree"), std::string::npos);
    EXPECT_FALSE(CanopyProfile::species(lodOf(0.0f, 2.0f, glm::vec3(0.5f))));
}

TEST(CanopyLayerSource, CombinedElevationAndCoverTexels) {
    PlantsParameters parameters;
    parameters.perHectare = 100.0;
    parameters.species = {{"a", 1.0}};
    CanopySpecies tall, short_;
    tall.height = 25.0;
    tall.crownWidth = 5.0;
    tall.albedo = {0.1, 0.3, 0.05};
    short_ = tall;
    short_.height = 5.0;
    short_.albedo = {0.5, 0.5, 0.5};
    const CanopyProfile tallProfile = CanopyProfile::make(parameters, {tall}).value();
    const CanopyProfile shortProfile = CanopyProfile::make(parameters, {short_}).value();
    const ConstantSource ground("ground", 123.0);
    const ConstantSource sparse("sparse", 0.2);  // channel 0: the density mask
    const ConstantSource dense("dense", 0.9);
    const std::vector<CanopyStand> stands{{&dense, shortProfile}, {&sparse, tallProfile}};
    const CanopyLayerSource elevation("cem", CanopyLayer::Elevation, &ground, stands);
    const CanopyLayerSource cover("cover", CanopyLayer::Cover, &ground, stands);
    TileEvaluator evaluator(TileFormat{32, 2});
    const TileKey key{12, 0, 2100, 1200};
    Result<TilePointer> heights = evaluator.tile(elevation, key);
    Result<TilePointer> covers = evaluator.tile(cover, key);
    ASSERT_TRUE(heights && covers);
    // The taller canopy wins: 25 m × cover(0.2) against 5 m × cover(0.9).
    const double winner = std::max(tallProfile.canopyHeight(0.2), shortProfile.canopyHeight(0.9));
    ASSERT_DOUBLE_EQ(winner, tallProfile.canopyHeight(0.2));
    for (const auto& [x, y] : {std::pair{-2, -2}, std::pair{0, 0}, std::pair{17, 33}}) {
        EXPECT_NEAR(heights.value()->at(x, y, 0), 123.0 + winner, 1e-4);
        EXPECT_NEAR(covers.value()->at(x, y, 1), 0.3, 1e-6);
        EXPECT_NEAR(covers.value()->at(x, y, 3), tallProfile.cover(0.2), 1e-6);
    }
    EXPECT_NE(elevation.contentHash(), cover.contentHash());
    const CanopyLayerSource other("cem", CanopyLayer::Elevation, &ground,
                                  {{&dense, tallProfile}, {&sparse, tallProfile}});
    EXPECT_NE(elevation.contentHash(), other.contentHash());
}

}  // namespace
}  // namespace sylva
