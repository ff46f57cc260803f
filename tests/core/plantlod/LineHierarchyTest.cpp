#include "sylva/core/plantlod/LineHierarchy.h"

#include <gtest/gtest.h>

#include "sylva/core/plantlod/SyntheticPlant.h"

namespace sylva {
namespace {

TEST(LineHierarchy, MergesNeverDisconnectTheSkeleton) {
    const PlantModel model = makeSyntheticPlant(300, 3);
    ASSERT_GT(model.skeleton.size(), 30u);
    const PrimitiveRasterizer rasterizer(model.boundsMinimum(), model.boundsMaximum(), 64, 4, 1);
    const glm::vec3 bark(0.3f, 0.2f, 0.1f);
    const LineHierarchyResult result =
        buildLineHierarchy(model.skeleton, bark, rasterizer, {}, {}, 0.0, 1.0);
    // Every merge removes one line: n − 1 merges leave a single line.
    ASSERT_EQ(result.merges.size(), model.skeleton.size() - 1);

    // Replay the merges and check connectivity after each one.
    LineSkeleton skeleton(model.skeleton, bark);
    ASSERT_TRUE(skeleton.connected(1e-4f));
    int step = 0;
    for (const LineMergeRecord& merge : result.merges) {
        ASSERT_TRUE(skeleton.valid(merge.kind, merge.first, merge.second)) << "merge " << step;
        const int created = skeleton.apply(merge.kind, merge.first, merge.second, ++step);
        EXPECT_EQ(created, merge.result);
        ASSERT_TRUE(skeleton.connected(1e-4f)) << "after merge " << step;
    }
    EXPECT_EQ(skeleton.aliveCount(), 1);
    // Weights add up to the total volume.
    double total = 0.0;
    for (std::size_t i = 0; i < model.skeleton.size(); ++i) {
        total += skeleton.nodes()[i].line.weight;
    }
    EXPECT_NEAR(skeleton.nodes().back().line.weight, total, 1e-6 * total);
    // The measured error grows overall: the last merge is worse than the first.
    EXPECT_GE(result.merges.back().measuredError, result.merges.front().measuredError);
}

TEST(LineHierarchy, StraightenOnlyAnOnlyChild) {
    // A trunk with two children: it cannot be straightened until they are combined.
    std::vector<SkeletonSegment> segments(3);
    segments[0] = {{0, 0, 0}, {0, 0, 1}, 0.1f, 0.08f, -1};
    segments[1] = {{0, 0, 1}, {0.5f, 0, 2}, 0.05f, 0.03f, 0};
    segments[2] = {{0, 0, 1}, {-0.5f, 0, 2}, 0.05f, 0.03f, 0};
    LineSkeleton skeleton(segments, glm::vec3(0.5f));
    EXPECT_FALSE(skeleton.canStraighten(0, 1));
    EXPECT_TRUE(skeleton.canCombine(1, 2));
    EXPECT_FALSE(skeleton.canCombine(0, 1));
    const int combined = skeleton.apply(LineMergeKind::Combine, 1, 2, 1);
    // Equal weights: the mean of both lines, still attached to the trunk's end.
    EXPECT_NEAR(skeleton.nodes()[combined].line.end.x, 0.0f, 1e-6f);
    EXPECT_NEAR(skeleton.nodes()[combined].line.start.z, 1.0f, 1e-6f);
    EXPECT_TRUE(skeleton.canStraighten(0, combined));
    const int straight = skeleton.apply(LineMergeKind::Straighten, 0, combined, 2);
    EXPECT_EQ(skeleton.nodes()[straight].line.start, glm::vec3(0, 0, 0));
    EXPECT_NEAR(skeleton.nodes()[straight].line.end.z, 2.0f, 1e-6f);
    EXPECT_TRUE(skeleton.connected(1e-5f));
}

}  // namespace
}  // namespace sylva
