// FrameBudget against a synthetic scene whose cost is known: frame = 50 ms fixed +
// 0.5 µs per primitive, 200,000 primitives at level 0 and half as many per coarser level
// (the controller does not know the 0.5). With a 120 ms budget the best level that fits
// is 2 (100 ms; level 1 costs 150 ms): the controller must get there, stay without
// reversals while the view is still, return to full detail when the budget allows it,
// and hand the renderer settings that coarsen with the level.
#include "sylva/render/viewer/FrameBudget.h"

#include <gtest/gtest.h>

#include <cmath>

namespace sylva::render {
namespace {

FrameMeasurement frameAt(int level, double primitivesAtZero, bool moved) {
    FrameMeasurement frame;
    frame.primitives = static_cast<std::size_t>(primitivesAtZero * std::pow(0.5, level));
    frame.vegetationMilliseconds = 0.0005 * double(frame.primitives);
    frame.frameMilliseconds = 50.0 + frame.vegetationMilliseconds;
    frame.cameraMoved = moved;
    return frame;
}

TEST(FrameBudget, SettlesOnTheFinestLevelThatFitsWithoutOscillating) {
    FrameBudget budget(120.0);
    EXPECT_EQ(budget.level(), 0);
    for (int frame = 0; frame < 10; ++frame) {
        budget.record(frameAt(budget.level(), 200000, false));
    }
    EXPECT_EQ(budget.level(), 2);
    const std::size_t reversals = budget.reversals();
    for (int frame = 0; frame < 200; ++frame) {
        budget.record(frameAt(budget.level(), 200000, false));
        EXPECT_LE(50.0 + 100.0 * std::pow(0.5, budget.level()), 120.0);
    }
    EXPECT_EQ(budget.level(), 2);
    EXPECT_EQ(budget.reversals(), reversals);
    // A lighter view (a tenth of the plants): full detail fits again, after the
    // hysteresis frames, and stays.
    for (int frame = 0; frame < 30; ++frame) {
        budget.record(frameAt(budget.level(), 20000, true));
    }
    EXPECT_EQ(budget.level(), 0);
}

// A frame whose fixed part (terrain, shading: proportional to the pixels drawn) alone
// exceeds the budget: 400 ms at full resolution, 100,000 primitives at 0.5 µs at every
// level. With 150 ms the controller must go past the vegetation's coarsest level to the
// resolution levels, settle on the first that fits (a quarter of the pixels: 100 + 50 ms
// ... above 150 ms, so an eighth: 50 + 50 ms) without reversals, and come back to full
// resolution and detail when the fixed part shrinks.
FrameMeasurement frameWithPixels(const FrameBudget& budget, double fixedAtFullResolution,
                                 bool moved = false) {
    FrameMeasurement frame;
    frame.cameraMoved = moved;
    frame.primitives = 100000;
    frame.vegetationMilliseconds = 50.0;
    const double scale = budget.renderScale();
    frame.frameMilliseconds = fixedAtFullResolution * scale * scale + 50.0;
    return frame;
}

TEST(FrameBudget, LowersTheResolutionWhenTheVegetationCannotMeetTheBudget) {
    FrameBudget budget(150.0);
    for (int frame = 0; frame < 20; ++frame) {
        budget.record(frameWithPixels(budget, 400.0));
    }
    EXPECT_EQ(budget.level(), FrameBudget::kLevels - 1);
    EXPECT_NEAR(budget.renderScale() * budget.renderScale(), 0.125, 1e-9);
    const std::size_t reversals = budget.reversals();
    for (int frame = 0; frame < 100; ++frame) {
        budget.record(frameWithPixels(budget, 400.0));
        EXPECT_EQ(budget.level(), FrameBudget::kLevels - 1);
    }
    EXPECT_EQ(budget.reversals(), reversals);
    // Still, a lighter view does not make the level finer (the viewer refines still
    // views itself); moving, it goes back to the full resolution and detail, then stays.
    for (int frame = 0; frame < 20; ++frame) {
        budget.record(frameWithPixels(budget, 20.0));
    }
    EXPECT_EQ(budget.level(), FrameBudget::kLevels - 1);
    for (int frame = 0; frame < 80; ++frame) {
        budget.record(frameWithPixels(budget, 20.0, true));
    }
    EXPECT_EQ(budget.level(), 0);
    EXPECT_EQ(budget.renderScale(), 1.0);
    // The vegetation levels draw at the full resolution.
    for (int level = 0; level < FrameBudget::kVegetationLevels; ++level) {
        EXPECT_EQ(FrameBudget::scaleOf(level), 1.0) << level;
    }
}

// The viewer's start-up frame is drawn at the coarsest level and is the model's first
// measurement: still frames keep that level, moving ones that predict room climb back.
TEST(FrameBudget, StartsAtTheLevelOfTheStartUpFrameAndClimbsOnlyWhileMoving) {
    FrameBudget budget(150.0);
    budget.startAt(FrameBudget::kLevels - 1);
    EXPECT_EQ(budget.level(), FrameBudget::kLevels - 1);
    for (int frame = 0; frame < 20; ++frame) {
        budget.record(frameWithPixels(budget, 20.0));  // 70 ms at full detail: room
    }
    EXPECT_EQ(budget.level(), FrameBudget::kLevels - 1);
    EXPECT_EQ(budget.changes(), 0u);
    for (int frame = 0; frame < 80; ++frame) {
        budget.record(frameWithPixels(budget, 20.0, true));
    }
    EXPECT_EQ(budget.level(), 0);
    EXPECT_EQ(budget.reversals(), 0u);
    FrameBudget none(0.0);
    none.startAt(FrameBudget::kLevels - 1);
    EXPECT_EQ(none.level(), 0) << "without a budget: always full detail";
}

TEST(FrameBudget, CoarserLevelsLowerQualityAndDropTheSmallestPlants) {
    FrameBudget budget(10.0);
    budget.record(frameAt(0, 1000000, false));  // 550 ms: far over budget
    ASSERT_GT(budget.level(), 0);
    VegetationSettings settings;
    const VegetationSettings coarse = budget.settingsFor(settings);
    EXPECT_LT(coarse.quality, settings.quality);
    EXPECT_GT(coarse.minimumPixels, settings.minimumPixels);
    FrameBudget none(0.0);
    none.record(frameAt(0, 1000000, false));
    EXPECT_EQ(none.level(), 0);
}

}  // namespace
}  // namespace sylva::render
