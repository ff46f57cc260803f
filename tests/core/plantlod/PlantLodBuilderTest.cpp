#include "sylva/core/plantlod/PlantLodBuilder.h"

#include <gtest/gtest.h>

#include <cmath>

#include "sylva/core/plantlod/PlodFile.h"
#include "sylva/core/plantlod/SyntheticPlant.h"

namespace sylva {
namespace {

PlantLodOptions smallOptions(int threads) {
    PlantLodOptions options;
    options.threads = threads;
    options.resolution = 64;
    options.views = 6;
    options.ambientOcclusionSamples = 16;
    options.seed = 42;
    return options;
}

const PlantModel& testPlant() {
    static const PlantModel model = makeSyntheticPlant(400, 9);
    return model;
}

const PlantLod& builtOnce() {
    static const PlantLod lod = [] {
        Result<PlantLod> built = buildPlantLod(testPlant(), smallOptions(2));
        EXPECT_TRUE(built.ok()) << (built.ok() ? "" : built.error().message);
        return std::move(built).value();
    }();
    return lod;
}

TEST(PlantLodBuilder, CoarserLevelsHaveNoMorePrimitivesAndNoLowerError) {
    const PlantLod& lod = builtOnce();
    ASSERT_GE(lod.levels.size(), 4u);  // 400 leaves → 100, 25, 6, 1 clusters
    EXPECT_EQ(lod.levels[0].ellipsoidCount, 400u);
    EXPECT_EQ(lod.levels.back().ellipsoidCount, 1u);
    for (std::size_t k = 1; k < lod.levels.size(); ++k) {
        const PlantLodLevel& finer = lod.levels[k - 1];
        const PlantLodLevel& coarser = lod.levels[k];
        EXPECT_LE(coarser.ellipsoidCount, finer.ellipsoidCount) << k;
        EXPECT_LE(coarser.lineCount, finer.lineCount) << k;
        EXPECT_GE(coarser.imageError, finer.imageError) << k;
        EXPECT_EQ(coarser.errorMinimum, finer.errorMaximum) << k;
        EXPECT_GT(coarser.errorMinimum, finer.errorMinimum) << k;
    }
}

TEST(PlantLodBuilder, SequentialArraysDrawAPrefix) {
    const PlantLod& lod = builtOnce();
    // Sorted coarse → fine, and at every level's error the drawn ellipsoids are a prefix
    // (after dropping those whose errorMinimum is above) with the level's count.
    for (std::size_t i = 1; i < lod.ellipsoids.size(); ++i) {
        ASSERT_GE(lod.ellipsoids[i - 1].errorMaximum, lod.ellipsoids[i].errorMaximum);
    }
    for (std::size_t i = 1; i < lod.lines.size(); ++i) {
        ASSERT_GE(lod.lines[i - 1].errorMaximum, lod.lines[i].errorMaximum);
    }
    for (const PlantLodLevel& level : lod.levels) {
        const float e = level.errorMinimum;
        std::size_t prefix = 0;
        while (prefix < lod.ellipsoids.size() && lod.ellipsoids[prefix].errorMaximum > e) {
            ++prefix;
        }
        std::uint32_t drawn = 0;
        for (std::size_t i = 0; i < prefix; ++i) {
            drawn += lod.ellipsoids[i].errorMinimum <= e ? 1 : 0;
        }
        EXPECT_EQ(drawn, level.ellipsoidCount);
    }
    // Ambient occlusion in range.
    for (const LodEllipsoid& e : lod.ellipsoids) {
        ASSERT_GE(e.ambientOcclusion, 0.0f);
        ASSERT_LE(e.ambientOcclusion, 1.0f);
    }
}

TEST(PlantLodBuilder, FixedSeedIsDeterministicAcrossThreadCounts) {
    Result<PlantLod> single = buildPlantLod(testPlant(), smallOptions(1));
    ASSERT_TRUE(single.ok());
    EXPECT_EQ(encodePlod(*single), encodePlod(builtOnce()));
}

TEST(PlantLodBuilder, RejectsEmptyAndBrokenModels) {
    PlantModel empty;
    empty.name = "nothing";
    Result<PlantLod> result = buildPlantLod(empty, smallOptions(1));
    ASSERT_FALSE(result.ok());
    EXPECT_EQ(
        result.error().message,
        "plant 'nothing' has neither leaves nor a branch skeleton: nothing to build a LoD from");
    PlantModel broken = makeSyntheticPlant(10, 1);
    broken.name = "broken";
    broken.skeleton[2].end.x = std::nanf("");
    result = buildPlantLod(broken, smallOptions(1));
    ASSERT_FALSE(result.ok());
    EXPECT_EQ(result.error().message,
              "plant 'broken': skeleton segment 2 has a non-finite coordinate");
}

TEST(PlantLodBuilder, ImportCalibratesLeafScaleNearTheAnalyticValue) {
    // The leaf texture is an ellipse: for a uniform elliptic disc the PCA radius is half
    // the semi-axis, so the calibrated scale should come out near 2.
    const PlantLod& lod = builtOnce();
    EXPECT_GT(lod.levels[0].primitiveScale, 1.5f);
    EXPECT_LT(lod.levels[0].primitiveScale, 2.6f);
}

}  // namespace
}  // namespace sylva
