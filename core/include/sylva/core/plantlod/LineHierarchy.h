// LineHierarchy: the branch skeleton simplified by successive merges (seed 001 §3.3.2,
// §3.4.2, Algorithm 2, Figs. 3.10–3.12).
//
// Merges: *straighten* a line with its only child (the child may have no siblings, so
// no branch loses its attachment) into one line from the parent's start to the child's
// end; *combine* two childless siblings into one line whose every property is the
// weight-interpolated mean. Weights start as the cone volumes and add up. After a
// straighten, the grandchildren's start points move to the nearest point of the new
// line, so every line still starts on its parent: merges never disconnect the skeleton.
// Any skeleton reduces to one line per root this way, and roots combine at the end.
//
// Choice of merges (Algorithm 2): gather N_new·N_local random valid merges, keep the
// N_new with the lowest local estimate (the angle between the two lines times the
// shorter length, Fig. 3.11), measure their image error and push them on a candidate
// heap; pop the best, re-measure it if the measurement is older than the last merge,
// apply it otherwise; prune the heap to N_cache. A measurement is "older than the last
// merge" only when that merge touched the candidate's lines or its screen footprint (the
// squared-error change of a merge depends on nothing else), so most cached candidates
// keep their exact measurement. The measured error is the sum of
// squared differences of the line images against the original skeleton over all views,
// updated incrementally: a merge re-renders only the screen rectangles its lines touch.
#pragma once

#include <cstdint>
#include <limits>
#include <vector>

#include "sylva/core/base/WorkerPool.h"
#include "sylva/core/plantlod/PlantLod.h"
#include "sylva/core/plantlod/PlantLodProgress.h"
#include "sylva/core/plantlod/PlantModel.h"
#include "sylva/core/plantlod/PrimitiveRasterizer.h"

namespace sylva {

enum class LineMergeKind : std::uint8_t { Straighten, Combine };

struct LineNode {
    LodLine line;
    int parent = -1;
    std::vector<int> children;
    bool alive = true;
    int birthStep = 0;  // 0: an original skeleton line; s: created by merge s (1-based)
    int deathStep = std::numeric_limits<int>::max();
};

struct LineMergePreview {
    LodLine merged;
    std::vector<std::pair<int, LodLine>> moved;  // grandchildren with moved starts
};

// The current state of the simplified skeleton.
class LineSkeleton {
public:
    // One line per segment, coloured `color`, weight = volume. Parents that are out of
    // range or not earlier in the list make a segment a root.
    LineSkeleton(const std::vector<SkeletonSegment>& segments, const glm::vec3& color);

    const std::vector<LineNode>& nodes() const { return nodes_; }
    int aliveCount() const { return aliveCount_; }
    bool canStraighten(int parent, int child) const;
    bool canCombine(int first, int second) const;
    bool valid(LineMergeKind kind, int first, int second) const;
    LineMergePreview preview(LineMergeKind kind, int first, int second) const;
    // Applies a valid merge as step `step`; returns the new node's index.
    int apply(LineMergeKind kind, int first, int second, int step);
    // Every live line's parent is live and the line starts on it (within `tolerance`
    // metres), and there are no more roots than at the start.
    bool connected(float tolerance) const;
    std::vector<int> siblings(int node) const;  // the live children of its parent (or roots)

private:
    std::vector<LineNode> nodes_;
    std::vector<int> roots_;
    int initialRoots_ = 0;
    int aliveCount_ = 0;
};

struct LineMergeRecord {
    LineMergeKind kind = LineMergeKind::Straighten;
    int first = -1;
    int second = -1;
    int result = -1;
    double measuredError = 0.0;  // RMSE of the line images against the original, after it
};

struct LineHierarchyOptions {
    int newCandidates = 4;      // N_new
    int localCandidates = 4;    // N_local
    int cachedCandidates = 16;  // N_cache
    std::uint32_t seed = 1;
    float widthScale = 1.0f;  // calibrated line width scale
    // Runs the candidate measurements in parallel (the result does not depend on it);
    // null: WorkerPool::shared().
    WorkerPool* pool = nullptr;
};

struct LineHierarchyResult {
    std::vector<LineNode> nodes;  // final state: every node ever created, with steps
    std::vector<LineMergeRecord> merges;
    float widthScale = 1.0f;
};

LineHierarchyResult buildLineHierarchy(const std::vector<SkeletonSegment>& segments,
                                       const glm::vec3& color,
                                       const PrimitiveRasterizer& rasterizer,
                                       const LineHierarchyOptions& options,
                                       const PlantLodProgressCallback& progress,
                                       double progressStart, double progressEnd);

}  // namespace sylva
