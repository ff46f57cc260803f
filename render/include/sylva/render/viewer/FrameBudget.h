// FrameBudget: time-critical choice of the vegetation level of detail for the viewer's
// `--budget-ms` (seed 002, Zach et al.; seed 000 ch. 8): every frame, the quality level
// predicted to fit the budget is chosen from a cost model refined by the frames measured
// while running. Used by the viewer (ViewerSession); public for its tests.
//
// Control variable: a ladder of levels, 0 = full detail (VegetationSettings quality 1,
// minimumPixels 1.5). Each coarser level divides `quality` by 1.4 (the renderer then
// tolerates 1.4× the screen error, so far plants reach their coarsest primitives first)
// and raises `minimumPixels` by 1.3 (the smallest plants on screen, the farthest, are
// left to the terrain texture first): the farthest and smallest degrade first, and a
// plant is never removed while it covers more than minimumPixels, so no hole opens
// where the terrain colour does not stand in.
//
// Cost model (seed 002 §4: cost linear in primitives): frame = fixed + c · primitives,
// where fixed (terrain, shading, read-back) and c (milliseconds per primitive drawn) are
// exponential averages of the measurements, and the primitive count of a neighbouring
// level is the current count times a ratio r per level learned from level changes made
// while the camera stood still (prior 0.6). Seed 002 optimises per object group; one
// global level is what VegetationSettings offers, so the knapsack reduces to a 1-D
// search along the ladder.
//
// Resolution (beyond the seeds, which budget the vegetation only): the terrain rings,
// the far-field canopy, shadows and shading are the fixed part of a frame, and on
// llvmpipe they alone exceeded the budget (issue 20: 280-750 ms at 1280x720 for 250 ms).
// So the ladder goes on past the vegetation's coarsest level with the render resolution:
// levels kVegetationLevels.. draw at renderScale() 0.71, 0.5, 0.35 of the window's width
// and height (half, a quarter, an eighth of the pixels; the viewer enlarges the image).
// The model takes the fixed part as proportional to the pixels drawn (it is mostly
// fragments on llvmpipe); where it is not, the next measurements correct it.
//
// Hysteresis: a coarser level is taken at once when the prediction for the current one
// exceeds the budget; a finer one only after 4 consecutive moving frames predicting it
// below 75 % of the budget (a still view only ever gets coarser: the viewer refines it
// at full detail once its tiles are in, so it cannot oscillate while still). Reversals
// (a change against the previous one) are counted.
#pragma once

#include <cstddef>

#include "sylva/render/vegetation/VegetationRenderer.h"

namespace sylva::render {

struct FrameMeasurement {
    double frameMilliseconds = 0;
    double vegetationMilliseconds = 0;
    std::size_t primitives = 0;  // ellipsoids + lines + instances (meshes, billboards)
    bool cameraMoved = false;
};

class FrameBudget {
public:
    static constexpr int kVegetationLevels = 8;  // levels that coarsen the vegetation
    static constexpr int kResolutionLevels = 3;  // then levels that lower the resolution
    static constexpr int kLevels = kVegetationLevels + kResolutionLevels;

    // budgetMilliseconds <= 0: no budget (always level 0).
    explicit FrameBudget(double budgetMilliseconds = 0);

    double budgetMilliseconds() const { return budget_; }
    int level() const { return level_; }
    // `settings` with the level's quality and minimum pixel size (relative to its values).
    VegetationSettings settingsFor(const VegetationSettings& settings) const {
        return settingsAt(settings, level_);
    }
    // The same at any `level` (0..kLevels-1).
    static VegetationSettings settingsAt(const VegetationSettings& settings, int level);
    // Fraction (0, 1] of the window's width and height to draw at the current level.
    double renderScale() const { return scaleOf(level_); }
    static double scaleOf(int level);
    // Before the first record(): the level the first frame is drawn at (the viewer's
    // start-up frame, at the coarsest level: nothing is known of the scene's cost yet).
    void startAt(int level);
    // Updates the model with a frame rendered at level(), then chooses the next level.
    void record(const FrameMeasurement& frame);
    // Predicted milliseconds of a frame at `level` like the last one.
    double predict(int level) const;
    std::size_t reversals() const { return reversals_; }
    std::size_t changes() const { return changes_; }

private:
    void changeLevel(int level);

    double budget_ = 0;
    int level_ = 0;
    double fixedMilliseconds_ = -1;         // at full resolution; < 0: not measured yet
    double millisecondsPerPrimitive_ = -1;  // < 0: not measured yet
    double ratio_ = 0.6;                    // primitives(level + 1) / primitives(level)
    double primitives_ = 0;                 // of the last frame
    int previousLevel_ = -1;                // level of the frame before the last
    double previousPrimitives_ = 0;
    int finerVotes_ = 0;
    int lastDirection_ = 0;
    std::size_t reversals_ = 0;
    std::size_t changes_ = 0;
};

}  // namespace sylva::render
