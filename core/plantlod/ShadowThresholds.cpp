#include "sylva/core/plantlod/ShadowThresholds.h"

#include <cmath>

#include "sylva/core/base/Check.h"
#include "sylva/core/base/WorkerPool.h"
#include "sylva/core/plantlod/PrimitiveRasterizer.h"

namespace sylva {

namespace {

// PrimitiveRasterizer with 8 views puts views 0–5 at 10° above the horizon and views 6
// and 7 at 55°.
constexpr int kViewCount = 8;
constexpr int kFirstHighView = 6;

struct ViewRange {
    int first, end;
};

ViewRange views(bool high) {
    return high ? ViewRange{kFirstHighView, kViewCount} : ViewRange{0, kFirstHighView};
}

PrimitiveRasterizer makeRasterizer(const PlantLod& lod, int resolution) {
    SYLVA_CHECK(resolution > 0);
    return PrimitiveRasterizer(lod.boundsMinimum, lod.boundsMaximum, resolution, kViewCount, 1);
}

double coveredShare(const RasterFrame& frame) {
    std::size_t covered = 0;
    for (float depth : frame.depth) {
        covered += std::isfinite(depth) ? 1 : 0;
    }
    return frame.depth.empty() ? 0.0 : double(covered) / double(frame.depth.size());
}

// The ellipsoids drawn at level `level`'s error (its interval's start).
std::vector<LodEllipsoid> levelEllipsoids(const PlantLod& lod, std::size_t level) {
    SYLVA_CHECK(level < lod.levels.size());
    const float error = lod.levels[level].errorMinimum;
    std::vector<LodEllipsoid> ellipsoids;
    for (const LodEllipsoid& e : lod.ellipsoids) {
        if (e.errorMinimum <= error && error < e.errorMaximum) {
            ellipsoids.push_back(e);
        }
    }
    return ellipsoids;
}

double coverage(const PrimitiveRasterizer& rasterizer, const std::vector<LodEllipsoid>& ellipsoids,
                float threshold, bool high) {
    const ViewRange range = views(high);
    double sum = 0.0;
    RasterFrame frame;
    for (int view = range.first; view < range.end; ++view) {
        rasterizer.clearFrame(frame);
        rasterizer.drawEllipsoids(ellipsoids, view, frame, {1.0f, threshold});
        sum += coveredShare(frame);
    }
    return sum / (range.end - range.first);
}

double sourceCoverage(const PrimitiveRasterizer& rasterizer, const PlantModel& model, bool high) {
    const ViewRange range = views(high);
    double sum = 0.0;
    RasterFrame frame;
    for (int view = range.first; view < range.end; ++view) {
        rasterizer.clearFrame(frame);
        rasterizer.drawMesh(model, PlantPart::Leaf, false, view, frame);
        sum += coveredShare(frame);
    }
    return sum / (range.end - range.first);
}

// The threshold at which `ellipsoids` cover `target` (bisection on the non-increasing
// coverage: lo covers at least the target, hi less).
float matchingThreshold(const PrimitiveRasterizer& rasterizer,
                        const std::vector<LodEllipsoid>& ellipsoids, double target, bool high) {
    float lo = 0.0f, hi = kMaximumShadowThreshold;
    if (coverage(rasterizer, ellipsoids, lo, high) <= target) {
        return lo;
    }
    if (coverage(rasterizer, ellipsoids, hi, high) >= target) {
        return hi;
    }
    for (int i = 0; i < 12; ++i) {
        const float middle = 0.5f * (lo + hi);
        (coverage(rasterizer, ellipsoids, middle, high) >= target ? lo : hi) = middle;
    }
    return 0.5f * (lo + hi);
}

}  // namespace

double sourceShadowCoverage(const PlantModel& model, const PlantLod& lod, bool high,
                            int resolution) {
    return sourceCoverage(makeRasterizer(lod, resolution), model, high);
}

double levelShadowCoverage(const PlantLod& lod, std::size_t level, float threshold, bool high,
                           int resolution) {
    const std::vector<LodEllipsoid> ellipsoids = levelEllipsoids(lod, level);
    if (threshold < 0.0f) {
        threshold = lod.levels[level].alphaThreshold;
    }
    return coverage(makeRasterizer(lod, resolution), ellipsoids, threshold, high);
}

std::vector<ShadowThreshold> shadowThresholds(const PlantModel& model, const PlantLod& lod,
                                              int resolution) {
    std::vector<ShadowThreshold> thresholds;
    for (const PlantLodLevel& level : lod.levels) {
        thresholds.push_back({level.alphaThreshold, level.alphaThreshold});
    }
    if (lod.ellipsoids.empty()) {
        return thresholds;
    }
    const PrimitiveRasterizer rasterizer = makeRasterizer(lod, resolution);
    const double targetLow = sourceCoverage(rasterizer, model, false);
    const double targetHigh = sourceCoverage(rasterizer, model, true);
    if (!(targetLow > 0.0 && targetHigh > 0.0)) {
        return thresholds;  // no leaves to compare with
    }
    // Levels and elevations are independent items (each writes its own entry).
    WorkerPool::shared().run(int(2 * lod.levels.size()), [&](int item) {
        const std::size_t k = std::size_t(item / 2);
        const bool high = item % 2 == 1;
        const std::vector<LodEllipsoid> ellipsoids = levelEllipsoids(lod, k);
        if (!ellipsoids.empty()) {
            (high ? thresholds[k].high : thresholds[k].low) =
                matchingThreshold(rasterizer, ellipsoids, high ? targetHigh : targetLow, high);
        }
    });
    return thresholds;
}

}  // namespace sylva
