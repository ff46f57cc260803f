#include "sylva/render/viewer/FrameBudget.h"

#include "sylva/core/base/Check.h"

#include <algorithm>
#include <cmath>

namespace sylva::render {
namespace {

constexpr double kQualityStep = 1.4;
constexpr double kPixelStep = 1.3;
constexpr double kAverage = 0.3;  // weight of the newest measurement
constexpr int kFinerVotes = 4;
constexpr double kFinerMargin = 0.75;

double blend(double old, double value) {
    return old < 0 ? value : old + kAverage * (value - old);
}

// The vegetation's ladder position of a level (the resolution levels keep its coarsest).
int vegetationLevel(int level) {
    return std::min(level, FrameBudget::kVegetationLevels - 1);
}

double pixelFraction(int level) {
    const double scale = FrameBudget::scaleOf(level);
    return scale * scale;
}

}  // namespace

FrameBudget::FrameBudget(double budgetMilliseconds) : budget_(budgetMilliseconds) {}

double FrameBudget::scaleOf(int level) {
    // Each resolution level halves the pixels: 1/sqrt(2) of the width and height.
    const int steps = std::clamp(level - (kVegetationLevels - 1), 0, kResolutionLevels);
    return std::pow(std::sqrt(0.5), steps);
}

VegetationSettings FrameBudget::settingsAt(const VegetationSettings& settings, int budgetLevel) {
    const int level = vegetationLevel(budgetLevel);
    VegetationSettings out = settings;
    out.quality = settings.quality / std::pow(kQualityStep, level);
    out.minimumPixels = settings.minimumPixels * std::pow(kPixelStep, level);
    return out;
}

double FrameBudget::predict(int level) const {
    const double fixed = std::max(fixedMilliseconds_, 0.0) * pixelFraction(level);
    const double perPrimitive = std::max(millisecondsPerPrimitive_, 0.0);
    return fixed + perPrimitive * primitives_ *
                       std::pow(ratio_, vegetationLevel(level) - vegetationLevel(level_));
}

void FrameBudget::startAt(int level) {
    SYLVA_CHECK(fixedMilliseconds_ < 0 && level >= 0 && level < kLevels);
    level_ = budget_ > 0 ? level : 0;
}

void FrameBudget::record(const FrameMeasurement& frame) {
    if (budget_ <= 0) {
        return;
    }
    const double primitives = static_cast<double>(frame.primitives);
    fixedMilliseconds_ = blend(
        fixedMilliseconds_, std::max(frame.frameMilliseconds - frame.vegetationMilliseconds, 0.0) /
                                pixelFraction(level_));
    if (primitives > 0) {
        millisecondsPerPrimitive_ =
            blend(millisecondsPerPrimitive_, frame.vegetationMilliseconds / primitives);
    }
    // One level apart with the camera still: the count ratio of the two levels.
    if (!frame.cameraMoved && previousLevel_ >= 0 && std::abs(previousLevel_ - level_) == 1 &&
        level_ < kVegetationLevels && previousLevel_ < kVegetationLevels && primitives > 0 &&
        previousPrimitives_ > 0) {
        const double measured = level_ > previousLevel_ ? primitives / previousPrimitives_
                                                        : previousPrimitives_ / primitives;
        ratio_ = std::clamp(std::exp(blend(std::log(ratio_), std::log(measured))), 0.2, 0.95);
    }
    previousLevel_ = level_;
    previousPrimitives_ = primitives;
    primitives_ = primitives;

    if (predict(level_) > budget_) {
        int coarser = level_ + 1;
        while (coarser < kLevels - 1 && predict(coarser) > budget_ * 0.9) {
            ++coarser;
        }
        changeLevel(std::min(coarser, kLevels - 1));
        return;
    }
    // Finer only while the camera moves: a still view is refined at full detail by the
    // viewer once its tiles are in, and while they arrive its frames' costs jump with
    // them (issue 20's bench: a cold still view went 10 -> 9 -> 10, a reversal).
    if (frame.cameraMoved && level_ > 0 && predict(level_ - 1) < budget_ * kFinerMargin) {
        if (++finerVotes_ >= kFinerVotes) {
            changeLevel(level_ - 1);
        }
        return;
    }
    finerVotes_ = 0;
}

void FrameBudget::changeLevel(int level) {
    finerVotes_ = 0;
    if (level == level_) {
        return;
    }
    const int direction = level > level_ ? 1 : -1;
    if (lastDirection_ != 0 && direction != lastDirection_) {
        ++reversals_;
    }
    lastDirection_ = direction;
    level_ = level;
    ++changes_;
}

}  // namespace sylva::render
